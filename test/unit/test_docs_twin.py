"""doc/twin.md's table of constants says what config/twin.yaml says."""
import io
import os
import re

import yaml

ROOT = os.path.join(os.path.dirname(__file__), '..', '..')
ROW = re.compile(r'^\| (`[a-z_]+\.[a-z_0-9]+`(?:, `[a-z_]+\.[a-z_0-9]+`)*) \| ([^|]+) \|', re.M)


def _read(path):
    with io.open(os.path.join(ROOT, path), encoding='utf-8') as stream:
        return stream.read()


def documented(text):
    """{'section.key': value as written} from the constants table of ``text``."""
    found = {}
    for keys, values in ROW.findall(text):
        names = [key.strip('`') for key in keys.split(', ')]
        written = [value.strip() for value in re.split(r',\s*(?![^\[]*\])', values.strip())]
        assert len(names) == len(written), 'row %s: %d keys, %d values' % (keys, len(names), len(written))
        found.update(zip(names, (yaml.safe_load(value) for value in written)))
    return found


def configured(data):
    """{'section.key': value} of every constant of the twin's YAML."""
    return {'%s.%s' % (section, key): value
            for section, table in data.items() for key, value in table.items()}


def test_every_constant_is_in_the_table_with_its_value():
    assert documented(_read('doc/twin.md')) == configured(yaml.safe_load(_read('config/twin.yaml')))


def test_a_row_with_a_wrong_value_differs():
    text = '| `bend.gear_ratio` | 88 | report | worm |\n| `wheel.kv_x`, `wheel.ki_x` | 0.02, 0.2 | estimate | PI |\n'
    assert documented(text) == {'bend.gear_ratio': 88, 'wheel.kv_x': 0.02, 'wheel.ki_x': 0.2}
    assert documented(text) != configured({'bend': {'gear_ratio': 87}, 'wheel': {'kv_x': 0.02, 'ki_x': 0.2}})
