"""The operator finds the quick start first: near the top of the README, on
operator.launch, with the panel's picture and the generated control table."""
import os

README = os.path.join(os.path.dirname(__file__), '..', '..', 'README.md')


def _quick_start():
    with open(README) as stream:
        lines = stream.read().splitlines()
    start = lines.index('## Operator quick start')
    end = next(i for i in range(start + 1, len(lines)) if lines[i].startswith('## '))
    return start, '\n'.join(lines[start:end])


def test_the_quick_start_comes_first_and_runs_the_operator_launch():
    start, text = _quick_start()
    assert start < 30
    assert 'roslaunch pirate operator.launch world:=' in text
    assert '](doc/images/virtual_panel.png)' in text
    assert '](doc/panel.md#what-every-control-does)' in text
    for button in ('**Play**', '**Stop**', 'confirms', 'pauses', 'resumes'):
        assert button in text, button
