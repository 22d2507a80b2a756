"""Every link in the documentation leads somewhere, and the README names what exists.

Each relative link and ``#section`` anchor in README.md, CONTRIBUTING.md and
doc/*.md must resolve: the file exists, and the anchor is a heading of it
by GitHub's slug rules (or a row's ``<a id>``); each repository path they
name in a code span (`src/...`, `config/...`) exists. Each ``make X`` the README or CONTRIBUTING.md
names is a Makefile target; each node and launch file of the package is in the README's table.
"""
import glob
import io
import os
import re

import pytest

ROOT = os.path.normpath(os.path.join(os.path.dirname(__file__), '..', '..'))
PAGES = ['README.md', 'CONTRIBUTING.md'] + sorted(
    os.path.relpath(path, ROOT) for path in glob.glob(os.path.join(ROOT, 'doc', '*.md')))

FENCE = re.compile(r'^ {0,3}(```|~~~).*?^ {0,3}\1[^\n]*$', re.M | re.S)
CODE_SPAN = re.compile(r'(`+)(.+?)\1', re.S)
LINK = re.compile(r'!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+"[^"]*")?\s*\)')
HEADING = re.compile(r'^ {0,3}#{1,6}\s+(.*?)\s*#*\s*$', re.M)
HTML_ANCHOR = re.compile(r'<a\s+(?:id|name)="([^"]+)"')
EXTERNAL = re.compile(r'^[a-z][a-z0-9+.-]*:', re.I)
#: A repository path in a code span: `src/pirate/...`, `config/...` (not a pattern with <, {, * or $).
TOP_DIRS = 'src|config|launch|bench|test|scripts|firmware|doc|urdf|rviz|nodes|msg|srv|action|cfg'
CODE_PATH = re.compile(r'`((?:%s)/[^`\s<{*$]*)`' % TOP_DIRS)


def _read(path):
    with io.open(os.path.join(ROOT, path), encoding='utf-8') as stream:
        return stream.read()


def _prose(text):
    """``text`` without fenced code blocks and code spans (links there are code, not links)."""
    return CODE_SPAN.sub('', FENCE.sub('', text))


def slug(heading):
    """GitHub's anchor for a Markdown heading: the rendered text, lower case,
    without punctuation other than ``-`` and ``_``, spaces as ``-``."""
    text = re.sub(r'!?\[([^\]]*)\]\([^)]*\)', r'\1', heading)     # a link's text
    text = re.sub(r'<[^>]+>', '', text).replace('`', '').replace('*', '')
    return re.sub(r'[^\w\- ]', '', text.strip().lower(), flags=re.U).replace(' ', '-')


def anchors(path):
    """Every anchor of a Markdown file: its headings' (repeated ones get -1,
    -2, ...) and its HTML ``<a id="...">`` ones (a table row's)."""
    text = FENCE.sub('', _read(path))
    found, seen = set(HTML_ANCHOR.findall(text)), {}
    for heading in HEADING.findall(text):
        base = slug(heading)
        count = seen.get(base, 0)
        seen[base] = count + 1
        found.add(base if count == 0 else '%s-%d' % (base, count))
    return found


def links(path):
    """The relative link targets of a Markdown file."""
    return [target for target in LINK.findall(_prose(_read(path))) if not EXTERNAL.match(target)]


def broken(page):
    """What is wrong with each relative link of ``page`` (a path under the root)."""
    problems = []
    for target in links(page):
        where, _, anchor = target.partition('#')
        path = os.path.normpath(os.path.join(os.path.dirname(page), where)) if where else page
        if not os.path.exists(os.path.join(ROOT, path)):
            problems.append('%s: no file %s' % (target, path))
        elif anchor and (not path.endswith('.md') or anchor not in anchors(path)):
            problems.append('%s: no heading #%s in %s' % (target, anchor, path))
    return problems


@pytest.mark.parametrize('page', PAGES)
def test_every_link_and_anchor_resolves(page):
    assert os.path.exists(os.path.join(ROOT, page)), '%s is missing' % page
    assert broken(page) == []


def missing_paths(page):
    """The repository paths ``page`` names in code spans that do not exist."""
    return [path for path in CODE_PATH.findall(_read(page))
            if not os.path.exists(os.path.join(ROOT, path))]


@pytest.mark.parametrize('page', PAGES)
def test_every_file_a_page_names_exists(page):
    assert missing_paths(page) == []


def test_every_make_target_the_readme_names_exists():
    named = set(re.findall(r'\bmake ([a-z][\w-]*)', _read('README.md') + _read('CONTRIBUTING.md')))
    targets = set(re.findall(r'^([\w-]+)\s*:', _read('Makefile'), re.M))
    assert named, 'the README names no make target'
    assert sorted(named - targets) == []


def test_the_readme_names_every_node_and_launch_file():
    readme = _read('README.md')
    nodes = sorted(os.listdir(os.path.join(ROOT, 'nodes')))
    launches = sorted(os.path.basename(p) for p in glob.glob(os.path.join(ROOT, 'launch', '*.launch')))
    assert [name for name in nodes + launches if '`%s`' % name not in readme] == []


@pytest.mark.parametrize('heading, anchor', [
    ('Operator quick start', 'operator-quick-start'),
    ("The run's plot", 'the-runs-plot'),
    ('`sim_robot` (`src/pirate/sim/node.py`) and `fil_robot`', 'sim_robot-srcpiratesimnodepy-and-fil_robot'),
    ('Layers and ROS', 'layers-and-ros'),
    ('[World format](twin.md): pieces', 'world-format-pieces'),
])
def test_anchors_follow_githubs_slug_rules(heading, anchor):
    assert slug(heading) == anchor


def test_a_link_to_a_missing_page_or_heading_is_reported(tmp_path, monkeypatch):
    (tmp_path / 'doc').mkdir()
    (tmp_path / 'doc' / 'a.md').write_text(u'# A\n\n## Real section\n\n| <a id="row"></a>row |\n\n'
                                           u'[b](b.md) [real](#real-section) [row](#row) [gone](#gone) '
                                           u'[web](https://example.org) `[code](nowhere.md)`\n')
    monkeypatch.setitem(globals(), 'ROOT', str(tmp_path))
    assert broken('doc/a.md') == ['b.md: no file doc/b.md', '#gone: no heading #gone in doc/a.md']


def test_a_moved_file_a_page_names_is_reported(tmp_path, monkeypatch):
    (tmp_path / 'doc').mkdir()
    (tmp_path / 'src').mkdir()
    (tmp_path / 'src' / 'here.py').write_text(u'')
    (tmp_path / 'doc' / 'a.md').write_text(u'`src/here.py`, `src/gone.py`, `config/guards_<mm>.yaml`\n')
    monkeypatch.setitem(globals(), 'ROOT', str(tmp_path))
    assert missing_paths('doc/a.md') == ['src/gone.py']
