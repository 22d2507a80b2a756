"""A fake sweep bench for the runner's tests: cases that succeed, fail,
crash (once, or always), hang or take a while, in no time and without a twin."""
import os
import random
import time

from pirate.sweep.cases import Sweep, case

PARAMETERS = ('n', 'behaviour')


def run(params, seed, settings):
    """One fake case: ``behaviour`` says what it does; a result drawn from ``seed``."""
    behaviour, marks = params['behaviour'], settings['marks']
    mark = os.path.join(marks, '%d' % params['n'])
    first = not os.path.exists(mark)
    open(mark, 'a').close()
    if behaviour == 'crash' or (behaviour == 'crash once' and first):
        os.abort()
    if behaviour == 'raise':
        raise RuntimeError('the case went wrong')
    if behaviour == 'hang':
        time.sleep(60.0)
    if behaviour == 'slow':
        time.sleep(settings.get('slow_s', 0.5))
    rng = random.Random(seed)
    outcome = 'FALSE success' if params['n'] % 4 == 3 else 'succeeded'
    return [{'outcome': outcome, 'robot_s': round(rng.uniform(5.0, 15.0), 3), 'primitives': ['a'] * params['n'],
             'truth': {'verdict': outcome == 'succeeded'}, 'figures': {'error_mm': rng.gauss(0.0, 5.0)}},
            {'variant': 'again', 'outcome': 'succeeded', 'robot_s': 1.0}][:settings.get('variants', 1)]


SWEEP = Sweep('fake', PARAMETERS, run, time_limit_s=30.0)


def cases(behaviours, seed=1):
    """One case per behaviour, numbered."""
    return [case(SWEEP, {'n': n, 'behaviour': b}, 'fake %s' % ('odd' if n % 2 else 'even'), seed)
            for n, b in enumerate(behaviours)]
