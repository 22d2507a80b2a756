"""The generated tables in doc/ are those the code generates (pirate.docs).

- every checked-in table equals what its generator returns now, else the
  test says to run `make docs`;
- a table is replaced between its two marker lines only, and a doc file
  without them is an error naming the markers.
"""
import pytest

from pirate import docs


def test_the_checked_in_doc_tables_are_current():
    stale = docs.stale()
    assert not stale, ('%s: a generated table differs from the code; run `make docs` and commit the result'
                       % ', '.join(stale))


def test_every_generated_table_is_in_its_doc_file():
    texts = docs.read()
    for path, marker, generator in docs.GENERATED:
        assert generator() in texts[path], (path, marker)


def test_a_table_is_replaced_between_its_markers_only():
    text = 'before\n%s\nold\nrows\n%s\nafter\n' % (docs.BEGIN % 'x', docs.END % 'x')
    filled = docs.fill(text, 'x', '| new |')
    assert filled == 'before\n%s\n| new |\n%s\nafter\n' % (docs.BEGIN % 'x', docs.END % 'x')
    assert docs.fill(filled, 'x', '| new |') == filled


def test_a_stale_table_is_seen():
    rows = (('page.md', 'x', lambda: '| new |'),)
    texts = {'page.md': '%s\n| old |\n%s\n' % (docs.BEGIN % 'x', docs.END % 'x')}
    assert docs.generated(texts, rows)['page.md'] != texts['page.md']


def test_a_doc_file_without_the_markers_is_refused_naming_them():
    rows = (('page.md', 'x', lambda: '| new |'),)
    with pytest.raises(docs.MissingMarkers, match='page.md: no lines "<!-- generated: x'):
        docs.generated({'page.md': 'no markers\n'}, rows)
