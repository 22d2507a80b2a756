"""Plots of a PAB run in the style of the report's Figs 6.1-6.7 (no ROS).

The report judges each behaviour by the joint angles, the orientation and the
guards against time, with a marker t1, t2, ... at each motion-primitive
transition (Fig 6.1), and by the bend efforts (Fig 6.2). One figure here
holds both, five panels sharing the time axis:

1. front module angle (board 21)
2. Bend I and Bend II (22, 23)
3. rotational module (25) and the orientation, with the straight band
   [1.52, 1.62] rad (Table 5.4) and pi/2 dotted, as the report's pink line
4. Bend III and Bend IV (26, 27)
5. bend efforts, mNm
6. the drive: odometry (mm) and wheel speed (mm/s), when the run has them

Cancels and aborts are red dashed lines named in the key; the tN labels
are stacked on as many rows as it takes for none to overlap
(:func:`label_rows`); the title says what ran (pirate.viz.bag_ros builds it
from the run's goals).

Everything takes plain data (lists of times and values, a list of
(t, primitive) markers), so tests can check what was drawn without a bag;
pirate.viz.bag_ros is the thin layer that reads one. ``plot_run`` returns the
panels it drew: the data, not a picture of it.
"""
import collections
import math
import textwrap

import matplotlib

from pirate.sequencer.goals import CODES
from pirate.sequencer.guards import CLAMP_BENDS

matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

#: Table 5.4: the straight region of the orientation, rad.
STRAIGHT_BAND = (1.52, 1.62)
UPRIGHT = math.pi / 2
#: The PABs' names by their goal codes (Pirate.action's ``name``).
PAB_NAMES = {code: name for name, code in CODES.items()}

#: A run: ``times`` s from the run's start; ``positions`` and ``efforts``
#: map joint names to lists as long as ``times`` (rad, mNm); ``orientation``
#: rad (Fig 4.7), as long as ``times``; ``markers`` [(t s, primitive)];
#: ``odometry`` mm and ``velocity`` mm/s as long as ``times`` (or empty);
#: ``events`` [(t s, 'cancelled ...' / 'aborted ...')]; ``title`` text;
#: ``spans`` [(start s, end s, PAB)] of the goals that ran; ``start_s`` the
#: recorded time (s) of t = 0, so a mission plot of the same bag shares the axis.
Run = collections.namedtuple('Run', 'times positions efforts orientation markers odometry velocity '
                                    'events title spans start_s', defaults=((), (), (), '', (), 0.0))
#: Above this many primitives a run plot marks its PABs' spans instead (a long mission ran 103).
MAX_PRIMITIVE_MARKERS = 24
#: Characters of a title line before it wraps (the figure is 12 in wide).
TITLE_WIDTH = 120
#: Label width used to keep tN labels apart, as a fraction of the time axis.
LABEL_GAP = 0.035

#: One panel: title, y label, [(label, times, values)], guard lines
#: [(label, value)], bands [(low, high)], reference lines [(label, value)].
Panel = collections.namedtuple('Panel', 'title ylabel series guards bands references')

#: The panels, top to bottom: (title, y label, joints drawn).
ANGLE_PANELS = (
    ('Front module', 'angle [rad]', ('front_tilt',)),
    ('Clamp front: Bend I, Bend II', 'angle [rad]', ('bend_i', 'bend_ii')),
    ('Rotational module and orientation', 'angle [rad]', ('rotation',)),
    ('Clamp rear: Bend III, Bend IV', 'angle [rad]', ('bend_iii', 'bend_iv')),
)
EFFORT_JOINTS = ('bend_i', 'bend_ii', 'bend_iii', 'bend_iv')

#: Legend labels: the module name and its PICO board, as the report's
#: "Angle 22" (Table 2.1).
LABELS = {
    'front_tilt': 'Front (21)', 'bend_i': 'Bend I (22)', 'bend_ii': 'Bend II (23)',
    'rotation': 'Rotation (25)', 'bend_iii': 'Bend III (26)', 'bend_iv': 'Bend IV (27)',
}


def transitions(feedback):
    """Markers from action feedback: [(t, goal_id, primitive)] -> [(t, primitive)].

    A marker is placed where the running primitive changes, or a new goal
    starts one; the feedback repeats the running primitive while it runs.
    An empty primitive (between primitives) places no marker but ends the
    previous one, so the same primitive run twice is marked twice.
    """
    markers = []
    previous = None
    for t, goal_id, primitive in feedback:
        key = (goal_id, primitive)
        if primitive and key != previous:
            markers.append((t, primitive))
        previous = key
    return markers


def _guard_entry(table, primitive):
    """(key, entry, part) of the guard config row a primitive name uses.

    Primitive names are the report's ('clamp rear custom', 'unclamp front
    partial', 'move front first'); the rows are config/guards_<mm>.yaml's
    ('clamp_rear_custom', 'unclamp_partial', 'move_front_first'), where a
    row without the part's name serves front and rear alike.
    """
    words = primitive.split()
    part = next((w for w in words if w in CLAMP_BENDS), None)
    candidates = ['_'.join(words)]
    if part is not None:
        candidates.append('_'.join(w for w in words if w != part))
    for key in candidates:
        if isinstance(table.get(key), dict):
            return key, table[key], part
    return None, None, part


def guard_lines(table, primitives):
    """Guard lines {joint: [(primitive, rad)]} of the primitives that ran.

    ``table`` is a parsed config/guards_<mm>.yaml (pirate.sequencer.guards): pair rows
    {outer: {guard}, inner: {guard}} for the bends of the primitive's part
    (pirate.sequencer.guards.CLAMP_BENDS), single rows {guard} for the front module.
    Primitives without a row (rotate, align) draw no guard line.
    """
    lines = collections.OrderedDict()
    for primitive in primitives:
        key, entry, part = _guard_entry(table or {}, primitive)
        if entry is None:
            continue
        if 'outer' in entry and part is not None:
            outer, inner = CLAMP_BENDS[part]
            found = [(outer, entry['outer']['guard']), (inner, entry['inner']['guard'])]
        elif 'guard' in entry:
            found = [('front_tilt', entry['guard'])]
        else:
            continue
        for joint, value in found:
            if all(float(value) != v for _, v in lines.get(joint, [])):
                lines.setdefault(joint, []).append((primitive, float(value)))
    return dict(lines)


def panels(run, guards=None):
    """The panels to draw for ``run``, with ``guards`` from guard_lines."""
    guards = guards or {}
    n = len(run.times)
    for name, values in list(run.positions.items()) + list(run.efforts.items()):
        if len(values) != n:
            raise ValueError('%s has %d samples for %d times' % (name, len(values), n))
    if len(run.orientation) != n:
        raise ValueError('orientation has %d samples for %d times' % (len(run.orientation), n))
    drawn = []
    for title, ylabel, joints in ANGLE_PANELS:
        series = [(LABELS[j], list(run.times), list(run.positions[j]))
                  for j in joints if j in run.positions]
        lines = [('%s %s' % (LABELS[j], label), value)
                 for j in joints for label, value in guards.get(j, [])]
        bands, references = [], []
        if 'rotation' in joints:
            series.append(('Orientation', list(run.times), list(run.orientation)))
            bands.append(STRAIGHT_BAND)
            references.append(('upright (pi/2)', UPRIGHT))
        drawn.append(Panel(title, ylabel, series, lines, bands, references))
    efforts = [(LABELS[j], list(run.times), list(run.efforts[j]))
               for j in EFFORT_JOINTS if j in run.efforts]
    drawn.append(Panel('Bend efforts', 'effort [mNm]', efforts, [], [], []))
    drive = [(label, list(run.times), list(values)) for label, values in
             (('Odometry [mm]', run.odometry), ('Wheel speed [mm/s]', run.velocity)) if len(values)]
    for label, _, values in drive:
        if len(values) != n:
            raise ValueError('%s has %d samples for %d times' % (label, len(values), n))
    if drive:
        drawn.append(Panel('Drive: odometry and wheel speed', 'mm, mm/s', drive, [], [], []))
    return drawn


def label_rows(times, span, gap=LABEL_GAP):
    """Row (0, 1, ...) of each tN label so that no two on a row are closer than ``gap * span``.

    Greedy, left to right: each label takes the lowest row whose last label
    is far enough; a burst of transitions stacks up instead of overlapping.
    """
    last, rows = [], []
    width = gap * (span or 1.0)
    for t in times:
        row = next((r for r, x in enumerate(last) if t - x >= width), len(last))
        if row == len(last):
            last.append(t)
        last[row] = t
        rows.append(row)
    return rows


KEY_COLUMNS = 3   # columns of the "tN  time  primitive" key under the plots


def pab_entries(spans):
    """Key entries ('P1', start s, 'PAB  12.3 s') of the PAB ``spans`` [(start, end, PAB)]."""
    return [('P%d' % i, start, '%s  %.1f s' % (pab, end - start)) for i, (start, end, pab) in enumerate(spans, 1)]


def marked(markers, spans):
    """What the plot marks: (primitive markers, PAB spans). A run with more
    than :data:`MAX_PRIMITIVE_MARKERS` primitives and its spans known marks
    the spans alone: 103 stacked primitive labels read as nothing."""
    if spans and len(markers) > MAX_PRIMITIVE_MARKERS:
        return [], list(spans)
    return list(markers), []


def render(drawn, markers, path, title=None, events=(), spans=(), xlim=None):
    """Draw ``drawn`` panels, the primitive ``markers`` and ``events`` to a PNG at ``path``.

    As in the report, each transition is a vertical line labelled tN; the
    key under the panels names the primitive of each tN (Tables 6.1-6.4).
    Events (cancel, abort) are red dashed lines, named in the key too.
    With many primitives the PAB ``spans`` (:func:`marked`) are shaded and
    labelled PN instead. ``xlim`` (s, s) fixes the time axis (shared with
    another plot of the same run); the title wraps instead of being clipped.
    """
    markers, spans = marked(markers, spans)
    entries = [('t%d' % i, t, primitive) for i, (t, primitive) in enumerate(markers, 1)]
    entries += pab_entries(spans)
    entries += [('!', t, text) for t, text in events]
    key_rows = max(1, math.ceil(len(entries) / KEY_COLUMNS))
    fig = plt.figure(figsize=(12, 2.1 * len(drawn) + 1.5 + 0.2 * key_rows))
    grid = fig.add_gridspec(len(drawn) + 1, 1,
                            height_ratios=[2.1] * len(drawn) + [0.2 * key_rows + 0.3])
    axes = []
    for row, panel in enumerate(drawn):
        ax = fig.add_subplot(grid[row], sharex=axes[0] if axes else None)
        axes.append(ax)
        for label, times, values in panel.series:
            ax.plot(times, values, label=label, linewidth=1.2)
        for low, high in panel.bands:
            ax.axhspan(low, high, color='tab:green', alpha=0.15, label='straight band')
        for label, value in panel.references:
            ax.axhline(value, color='magenta', linestyle=':', linewidth=1.2, label=label)
        for label, value in panel.guards:
            ax.axhline(value, color='grey', linestyle='--', linewidth=0.8)
            ax.annotate(label, (1.0, value), xycoords=('axes fraction', 'data'),
                        fontsize=6, color='dimgrey', ha='right', va='bottom')
        for t, _ in markers:
            ax.axvline(t, color='black', linestyle='-', linewidth=0.6, alpha=0.5)
        for t, _ in events:
            ax.axvline(t, color='red', linestyle='--', linewidth=1.2)
        for i, (start, end, _) in enumerate(spans):
            ax.axvspan(start, end, color='tab:blue' if i % 2 else 'tab:orange', alpha=0.08)
        ax.set_title(panel.title, fontsize=9, loc='right')
        ax.set_ylabel(panel.ylabel, fontsize=8)
        ax.grid(True, alpha=0.3)
        if panel.series:
            ax.legend(fontsize=7, loc='upper left', bbox_to_anchor=(1.01, 1.0))
        if row < len(drawn) - 1:
            ax.tick_params(labelbottom=False)
    times = [t for _, t, _ in entries]
    span = (max(times) - min(times)) if times else 1.0
    for (label, t, _), row in zip(entries, label_rows(times, span)):
        axes[0].annotate(label, (t, 1.02 + 0.1 * row), xycoords=('data', 'axes fraction'),
                         fontsize=7, ha='center', color='red' if label == '!' else 'black')
    if xlim is not None:
        axes[0].set_xlim(*xlim)
    axes[-1].set_xlabel('time [s]')
    key = fig.add_subplot(grid[len(drawn)])
    key.axis('off')
    for i, (label, t, text) in enumerate(entries):
        column, row = divmod(i, key_rows)
        key.text(column / KEY_COLUMNS, 1.0 - (row + 0.5) / key_rows,
                 '%-3s %6.2f s  %s' % (label, t, text), fontsize=8, va='center',
                 family='monospace', transform=key.transAxes, color='red' if label == '!' else 'black')
    if title:
        fig.suptitle(textwrap.fill(title, TITLE_WIDTH), fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def plot_run(run, path, guards=None, title=None, xlim=None):
    """Plot ``run`` to ``path`` (title: ``title``, else the run's); return (panels, markers drawn)."""
    drawn = panels(run, guards)
    render(drawn, run.markers, path, title or run.title or None, run.events, run.spans, xlim)
    return drawn, marked(run.markers, run.spans)[0]
