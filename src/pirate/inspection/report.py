"""``rosrun pirate inspection_report RUN``: a run's self-contained HTML report.

One file, no external assets (frames inlined as base64 data URIs, the map an
inline SVG): the map with the route driven and the findings on it, every
finding with its frames, its distance from the launch pit and its position
on the map with its uncertainty, the route's timeline (from the mission
executive's log, when the run has one) and the dig list. Pure: no ROS.
"""
import argparse
import base64
import html
import os
import sys

from pirate.inspection import findings as fd
from pirate.inspection import mission_log, store
from pirate.world import network as nw

SVG_WIDTH, SVG_HEIGHT, SVG_MARGIN = 760, 420, 40
PIPE_MAX_PX = 12        # a short network's pipe drawn no wider than this
LABEL_PX = 14           # labels of findings at one place are stacked this far apart
SAMPLE_M = 0.01
STYLE = """body{font-family:sans-serif;margin:2em;max-width:1000px}
table{border-collapse:collapse}td,th{border:1px solid #999;padding:4px 8px;text-align:left}
.finding{border:1px solid #ccc;margin:1em 0;padding:0.5em 1em}
.finding figure{display:inline-block;margin:4px}.finding img{width:320px;image-rendering:pixelated}
.warn{color:#a60}"""


class ReportError(ValueError):
    """A report that cannot be written: says why."""


def run_folder(run, root=store.DEFAULT_ROOT):
    """The folder of ``run``: a path, or a run name under ``root``."""
    if os.path.sep in run or os.path.isdir(run):
        return run
    return os.path.join(root, run)


def _e(text):
    return html.escape(str(text))


def _project(points):
    """2-D (SVG) coordinates of 3-D points: the two world axes along which
    the network spreads most, scaled into the drawing; the scale (px/m)
    and the drawing's height (px, as much as the network needs)."""
    spans = [max(p[k] for p in points) - min(p[k] for p in points) for k in range(3)]
    a, b = sorted(sorted(range(3), key=lambda k: -spans[k])[:2])
    low_a, low_b = min(p[a] for p in points), min(p[b] for p in points)
    scale = min((SVG_WIDTH - 2 * SVG_MARGIN) / max(spans[a], 1e-3),
                (SVG_HEIGHT - 2 * SVG_MARGIN) / max(spans[b], 1e-3))
    height = spans[b] * scale + 2 * SVG_MARGIN

    def to_svg(point):
        return SVG_MARGIN + (point[a] - low_a) * scale, height - SVG_MARGIN - (point[b] - low_b) * scale
    return to_svg, scale, height


def _along(network, from_m, to_m):
    count = max(1, int(abs(to_m - from_m) / SAMPLE_M))
    return [network.locate(from_m + (to_m - from_m) * i / count)[1].origin for i in range(count + 1)]


def _polyline(to_svg, points, style):
    return '<polyline points="%s" style="fill:none;%s"/>' % (
        ' '.join('%.1f,%.1f' % to_svg(p) for p in points), style)


def map_svg(network, launch_m, reached_m, findings):
    """The network (grey), the route driven from the launch pit to the
    farthest place reached (green), the named points and each finding
    (red, numbered, its uncertainty as an orange span along the pipe)."""
    pipe = _along(network, 0.0, network.length)
    stubs = [[p.stub.origin, tuple(o + p.diameter * a for o, a in zip(p.stub.origin, p.stub.axes[0]))]
             for p in network.pieces if p.stub is not None]
    to_svg, scale, height = _project(pipe + [s for stub in stubs for s in stub])
    width = min(PIPE_MAX_PX, max(2.0, network.pieces[0].diameter * scale))
    parts = [_polyline(to_svg, pipe, 'stroke:#bbb;stroke-width:%.1f' % width)]
    parts += [_polyline(to_svg, s, 'stroke:#ddd;stroke-width:%.1f' % width) for s in stubs]
    if reached_m is not None and abs(reached_m - launch_m) > 1e-3:
        parts.append(_polyline(to_svg, _along(network, launch_m, reached_m), 'stroke:#2a2;stroke-width:3'))
    for name, along in sorted(network.points.items()):
        x, y = to_svg(network.locate(along)[1].origin)
        parts.append('<circle cx="%.1f" cy="%.1f" r="4" fill="#26c"/><text x="%.1f" y="%.1f" font-size="12" '
                     'fill="#26c">%s</text>' % (x, y, x + 6, y + 16, _e(name)))
    labels = []
    for finding in findings:
        pos = finding['position']
        along, spread = pos['along_mm'] / 1000.0, pos['uncertainty_mm'] / 1000.0
        span = _along(network, max(0.0, along - spread), min(network.length, along + spread))
        x, y = to_svg(network.locate(along)[1].origin)
        label_y = y - 7
        while any(abs(x - lx) < LABEL_PX and abs(label_y - ly) < LABEL_PX for lx, ly in labels):
            label_y -= LABEL_PX
        labels.append((x, label_y))
        parts.append(_polyline(to_svg, span, 'stroke:orange;stroke-width:6;stroke-opacity:0.6'))
        parts.append('<circle cx="%.1f" cy="%.1f" r="6" fill="#d22"/><text x="%.1f" y="%.1f" font-size="13" '
                     'font-weight="bold" fill="#d22">%d</text>' % (x, y, x + 7, label_y, finding['number']))
    return ('<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" viewBox="0 0 %d %d" id="map">%s</svg>'
            % (SVG_WIDTH, height, SVG_WIDTH, height, ''.join(parts)))


def _image(folder, camera, name, warnings):
    path = os.path.join(folder, name)
    if not os.path.exists(path):
        warnings.append('%s: missing (named by a finding)' % path)
        return '<p class="warn">frame %s missing</p>' % _e(name)
    with open(path, 'rb') as stream:
        data = base64.b64encode(stream.read()).decode('ascii')
    return ('<figure><img alt="%s" src="data:image/png;base64,%s"/><figcaption>%s camera</figcaption></figure>'
            % (_e(name), data, _e(camera)))


def _where(pos):
    return ('%.0f mm from the launch pit along the route (+/- %.0f mm); %s, %.0f mm from %s; %s'
            % (pos['from_launch_pit_mm'], pos['uncertainty_mm'], pos['segment'], pos['from_last_junction_mm'],
               pos['last_junction'], pos['clock_text']))


def finding_html(folder, finding, warnings):
    """One finding: number, kind, note, time, where, its frames."""
    frames = finding.get('frames') or {}
    images = ''.join(_image(folder, camera, frames[camera], warnings) for camera in sorted(frames))
    missing = ''.join('<p class="warn">%s camera: %s</p>' % (_e(c), _e(why))
                      for c, why in sorted((finding.get('no_frame') or {}).items()))
    return ('<div class="finding" id="finding-%d"><h3>Finding %d: %s</h3><p>%s</p><p>%s (%s)</p>'
            '<p>Where: %s</p>%s%s</div>' % (
                finding['number'], finding['number'], _e(finding.get('kind', 'other')), _e(finding.get('note', '')),
                _e(finding.get('wall_time', '')), 'robot time %.1f s' % finding.get('stamp_s', 0.0),
                _e(_where(finding['position'])), images, missing))


def dig_list_html(findings):
    rows = ''.join('<tr><td>%d</td><td>%s</td><td>%s</td><td>%s</td></tr>' % (
        f['number'], _e(f.get('kind', 'other')), _e(line), _e(f['position']['clock_text']))
        for f, line in fd.dig_list(findings))
    return ('<table id="dig-list"><tr><th>finding</th><th>kind</th><th>where to dig</th><th>clock</th></tr>%s'
            '</table>' % rows)


def _time(t):
    """Robot time as '12.3 s'; anything else as it is."""
    return '%.1f s' % t if isinstance(t, (int, float)) else ('' if t is None else str(t))


def timeline_html(events, findings):
    """The missions' events (the recorder's timeline and the executive's
    log; with the findings, by robot time, when every event has a time), in
    order; a note when the run has none."""
    if not events:
        return '<p id="timeline">No mission in this run: no timeline.</p>'
    rows = [(t, text, along) for t, text, along in events]
    if all(isinstance(t, (int, float)) for t, _, _ in rows):
        rows += [(f.get('stamp_s'), 'finding %d marked: %s' % (f['number'], f.get('kind')),
                  f['position']['along_mm']) for f in findings if isinstance(f.get('stamp_s'), (int, float))]
        rows.sort(key=lambda r: r[0])
    cells = ''.join('<tr><td>%s</td><td>%s</td><td>%s</td></tr>' % (
        _e(_time(t)), _e('' if along is None else '%.0f' % along), _e(text)) for t, text, along in rows)
    return '<table id="timeline"><tr><th>time</th><th>along (mm)</th><th>event</th></tr>%s</table>' % cells


def _network(about, map_override, warnings):
    name = map_override or about.get('map')
    if not name:
        warnings.append('the run names no map (run.json): the report has no map; give --map')
        return None
    try:
        return nw.load(nw.world_path(name))
    except nw.WorldError as error:
        raise ReportError('map of the run: %s' % error)


def build(folder, map_override=None, log_path=None):
    """(HTML text, warnings) of the run at ``folder``; :class:`store.RunError`
    or :class:`ReportError` when it cannot be made."""
    findings, warnings = store.read_findings(folder)
    if not findings:
        raise store.RunError('%s: %s has no finding (nothing marked, or every line cut short)'
                             % (folder, store.FINDINGS_FILE))
    about = store.read_about(folder)
    network = _network(about, map_override, warnings)
    events = []
    for path in (os.path.join(folder, store.TIMELINE_FILE),
                 log_path or os.path.join(folder, mission_log.MISSION_LOG_FILE)):
        read, log_warnings = mission_log.read_events(path)
        events += read
        warnings += log_warnings
    alongs = [f['position']['along_mm'] / 1000.0 for f in findings] + [a / 1000.0 for _, _, a in events if a]
    launch_m = about.get('launch_pit_mm', 0.0) / 1000.0
    reached = max(alongs, key=lambda a: abs(a - launch_m)) if alongs else None
    body = ['<h1>Inspection report: %s</h1>' % _e(about.get('run', os.path.basename(os.path.normpath(folder)))),
            '<p>Map: %s; launch pit at %.0f mm along the map; %d findings.</p>'
            % (_e(about.get('map', map_override or 'unknown')), launch_m * 1000, len(findings)),
            '<h2>Dig list</h2>', dig_list_html(findings),
            '<h2>Map and route driven</h2>',
            map_svg(network, launch_m, reached, findings) if network else '<p class="warn">no map</p>',
            '<h2>Findings</h2>'] + [finding_html(folder, f, warnings) for f in findings]
    body += ['<h2>Timeline</h2>', timeline_html(events, findings)]
    if warnings:
        body += ['<h2>Warnings</h2><ul>%s</ul>' % ''.join('<li class="warn">%s</li>' % _e(w) for w in warnings)]
    page = ('<!DOCTYPE html><html><head><meta charset="utf-8"><title>Inspection report %s</title><style>%s</style>'
            '</head><body>%s</body></html>' % (_e(about.get('run', '')), STYLE, '\n'.join(body)))
    return page, warnings


def main(argv=None):
    parser = argparse.ArgumentParser(prog='inspection_report', description=__doc__.split('\n')[0])
    parser.add_argument('run', help='run folder, or a run name under --root')
    parser.add_argument('--root', default=store.DEFAULT_ROOT, help='runs folder (default %(default)s)')
    parser.add_argument('--out', help='HTML file to write (default RUN/report.html)')
    parser.add_argument('--map', help='world file or name (default: the run\'s map)')
    parser.add_argument('--mission-log', help='the mission executive\'s JSON Lines log (default RUN/%s)'
                        % mission_log.MISSION_LOG_FILE)
    args = parser.parse_args(argv)
    folder = run_folder(args.run, args.root)
    try:
        page, warnings = build(folder, args.map, args.mission_log)
        out = args.out or os.path.join(folder, 'report.html')
        with open(out, 'w') as stream:
            stream.write(page)
    except (store.RunError, ReportError, OSError) as error:
        print('inspection_report: %s' % error, file=sys.stderr)
        return 1
    for warning in warnings:
        print('warning: %s' % warning, file=sys.stderr)
    print(out)
    return 0
