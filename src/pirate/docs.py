"""The tables in doc/ that are generated from the code: ``make docs`` writes them.

:data:`GENERATED` lists each one as (doc file, marker name, generator): the
generator, a function of no arguments, returns the Markdown that stands
between the file's two marker lines::

    <!-- generated: junction-table (make docs) -->
    ...
    <!-- end generated: junction-table -->

A page adds a generated table with one row here and the two marker lines
in its file. test/unit/test_docs_current.py fails while a checked-in table
differs from what its generator returns. Pure apart from :func:`write`.
"""
import io
import os
import re

from pirate import paths
from pirate.panel import doc_table
from pirate.sequencer.pabs import clamp, drive, home, junction_table
from pirate.sequencer.pabs.table_doc import markdown
from pirate.sim import twin_sources

GENERATED = (
    ('doc/sequencer.md', 'clamp-table', lambda: markdown(clamp.MACHINE)),
    ('doc/sequencer.md', 'drive-table', lambda: markdown(drive.MACHINE)),
    ('doc/sequencer.md', 'home-table', lambda: markdown(home.MACHINE)),
    ('doc/sequencer.md', 'junction-table', lambda: markdown(junction_table.MACHINES['front'])),
    ('doc/sequencer.md', 'junction-rear-first-table', lambda: markdown(junction_table.MACHINES['rear'])),
    ('doc/panel.md', 'panel-controls', doc_table.generate),
    ('doc/twin.md', 'twin-constants', twin_sources.markdown),
)

BEGIN = '<!-- generated: %s (make docs) -->'
END = '<!-- end generated: %s -->'


class MissingMarkers(ValueError):
    """A doc file lacks the marker lines of one of its generated tables."""


def fill(text, marker, body):
    """``text`` with what stands between ``marker``'s two lines replaced by ``body``."""
    pattern = re.compile(r'(%s)\n(?:.*?\n)?(%s)' % (re.escape(BEGIN % marker), re.escape(END % marker)), re.DOTALL)
    if not pattern.search(text):
        raise MissingMarkers('no lines "%s" ... "%s"' % (BEGIN % marker, END % marker))
    return pattern.sub(lambda match: '%s\n%s\n%s' % (match.group(1), body, match.group(2)), text, count=1)


def generated(texts, rows=GENERATED):
    """{doc file: its text with every generated table filled}, from ``texts`` ({doc file: text})."""
    result = dict(texts)
    for path, marker, generator in rows:
        try:
            result[path] = fill(result[path], marker, generator())
        except MissingMarkers as missing:
            raise MissingMarkers('%s: %s' % (path, missing))
    return result


def read(root=paths.PACKAGE_DIR, rows=GENERATED):
    """{doc file: its checked-in text} of every file ``rows`` name."""
    texts = {}
    for path in sorted({row[0] for row in rows}):
        with io.open(os.path.join(root, path), encoding='utf-8') as stream:
            texts[path] = stream.read()
    return texts


def stale(root=paths.PACKAGE_DIR, rows=GENERATED):
    """The doc files whose checked-in tables differ from what the code generates."""
    texts = read(root, rows)
    fresh = generated(texts, rows)
    return sorted(path for path in texts if fresh[path] != texts[path])


def write(root=paths.PACKAGE_DIR, rows=GENERATED):
    """Regenerate every table in place; the doc files that changed."""
    texts = read(root, rows)
    fresh = generated(texts, rows)
    changed = sorted(path for path in texts if fresh[path] != texts[path])
    for path in changed:
        with io.open(os.path.join(root, path), 'w', encoding='utf-8') as stream:
            stream.write(fresh[path])
    return changed
