"""The sweep's loop, on any engine: every case once, a case that crashed or
hung once more, then recorded as such; records written as they finish.

An engine (:mod:`pirate.sweep.engine`) has ``submit(case)`` and
``results()``: an iterator of (case, status, payload) as cases finish,
status 'ok' (payload: the records), 'crashed' or 'hang' (payload: why),
that ends when nothing is pending.
"""
from pirate.sweep import records

#: How many times a case runs before its crash or hang is its record.
ATTEMPTS = 2


def run(cases, engine, write, progress, provenance):
    """Run ``cases`` on ``engine``; ``write(records)`` each finished case's
    records; ``provenance``: the runner's commit and engine version, for the
    record of a case that never finished. Returns how many cases crashed or hung."""
    attempts = {}
    for case in cases:
        engine.submit(case)
    lost = 0
    for case, status, payload in engine.results():
        tried = attempts[case['key']] = attempts.get(case['key'], 0) + 1
        if status == 'ok':
            for record in payload:
                record['attempts'] = tried
            found = payload
        elif tried < ATTEMPTS:
            progress.note('%s: %s (%s); running it once more' % (case['key'], status, payload))
            engine.submit(case)
            continue
        else:
            lost += 1
            found = [records.failed(case, status, payload, tried, provenance)]
        write(found)
        progress.finished(found)
    progress.end()
    return lost
