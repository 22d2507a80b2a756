"""doc/interfaces.md names every interface the code has.

Every topic, service and action of :mod:`pirate.names`, every message,
service and action type of msg/, srv/ and action/, and every private
parameter a node reads (``get_param('~name')``) appears on the page.
"""
import glob
import io
import os
import re

from pirate import names

ROOT = os.path.join(os.path.dirname(__file__), '..', '..')
PRIVATE_PARAM = re.compile(r"""get_param\(\s*['"](~\w+)['"]""")


def _read(path):
    with io.open(os.path.join(ROOT, path), encoding='utf-8') as stream:
        return stream.read()


def _page():
    return _read(os.path.join('doc', 'interfaces.md'))


def private_params():
    """Every ``~name`` a module of the library reads with get_param."""
    found = set()
    for path in glob.glob(os.path.join(ROOT, 'src', 'pirate', '**', '*.py'), recursive=True):
        found |= set(PRIVATE_PARAM.findall(_read(path)))
    return found


def test_every_topic_service_and_action_name_is_documented():
    graph_names = [value for key, value in vars(names).items()
                   if key.isupper() and isinstance(value, str) and value.startswith('/')]
    assert len(graph_names) > 15
    assert [name for name in graph_names if '`%s`' % name not in _page()] == []


def test_every_message_service_and_action_type_is_documented():
    kinds = [('msg', '.msg', ''), ('srv', '.srv', ''), ('action', '.action', 'Action')]
    types = ['pirate/%s%s' % (os.path.basename(path)[:-len(ext)], suffix)
             for folder, ext, suffix in kinds for path in glob.glob(os.path.join(ROOT, folder, '*' + ext))]
    assert [kind for kind in types if '`%s' % kind not in _page()] == []


def test_every_private_parameter_a_node_reads_is_documented():
    params = private_params()
    assert '~stale_after' in params
    assert [p for p in sorted(params) if not re.search(r'`%s[`/]' % re.escape(p), _page())] == []
