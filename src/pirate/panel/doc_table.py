"""What each panel control does, as the Markdown table of doc/panel.md.

Generated from the panel map (``config/nanokontrol2.yaml``), so the page
cannot disagree with the YAML: ``controls_table`` is pure (a loaded map in,
text out); ``generate`` reads the package's map, for ``make docs``.
"""
import os

from pirate import paths
from pirate.panel import config

#: The panel map the operator launches use by default.
PANEL_MAP = os.path.join(paths.CONFIG_DIR, 'nanokontrol2.yaml')
HEADER = ('| control | channel | manual mode | PAB mode |\n'
          '|---------|---------|-------------|----------|')


def controls_table(params):
    """The Markdown table of a panel map (the dict the YAML loads to).

    One row per channel in channel order: the control, its MIDI channel,
    its job in manual mode and in PAB mode (a mission button's job in PAB
    mode is marked "mission:"); a control with no job says "not used".
    Raises :class:`pirate.panel.config.ConfigError` for a bad map.
    """
    panel = config.from_params(params)
    rows = [_row(entry, panel.mission_buttons.get(entry.channel))
            for _, entry in sorted(panel.channels.items())]
    return '\n'.join([HEADER] + rows)


def _row(entry, mission_button):
    manual = entry.function if config.MANUAL in entry.modes else ''
    pab = entry.function if config.PAB in entry.modes else ''
    if mission_button is not None:
        pab = 'mission: %s' % mission_button.function
    if not (manual or pab):
        manual = pab = 'not used'
    return '| %s | %d | %s | %s |' % (_cell(entry.control), entry.channel, _cell(manual), _cell(pab))


def _cell(text):
    """``text`` safe inside a Markdown table cell."""
    return str(text).replace('|', '\\|').replace('\n', ' ')


def generate(path=PANEL_MAP):
    """The table of the panel map at ``path`` (default: the package's)."""
    import yaml
    with open(path) as stream:
        return controls_table(yaml.safe_load(stream))
