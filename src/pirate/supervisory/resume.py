"""Taking up, from its log, a mission whose executive died.

The executive's log (pirate.supervisory.mission_log) holds, as it goes,
what the mission was asked (its start record's ``goal``), a record when
each step starts and one when it succeeds, each with the localiser's state
then (pirate.supervisory.localiser ``state``). From these and the robot's
odometry now, :func:`take_up` says where the mission goes on:

- the first step not known to have succeeded runs first. One that had
  started when the executive died runs as after a pause: re-clamped if the
  robot no longer is, a Drive only for what is left of it from the
  estimate, a junction PAB from where the robot is (the Pirate Server
  keeps what a turn cancelled half round left, for the same goal re-sent);
- the estimate goes on from the last anchor by the odometry since, so its
  uncertainty has grown by that distance;
- a turn that may have sensed its junction (the robot moved, during the
  step, as far as the earliest place the map and the uncertainty allow) is
  re-sent as it is; straight on through a T-joint, the step runs again
  only if the robot moved less than the junction's length during it (its
  front V cannot have passed the junction, whatever it had sensed); else
  the crossing may have begun and cannot be resumed.

It refuses (:class:`CannotResume`, with the reason) a log with no mission,
a mission that ended, a log without the goal or the estimate, a map that no
longer loads or plans another route, an unknown odometry, and an odometry
that moved more than the interrupted step could have moved it (reset, or
the robot moved by hand). Pure: no ROS.
"""
import collections

import yaml

from pirate.sequencer.junctions import is_turn
from pirate.supervisory.executive import Entry
from pirate.supervisory.localiser import restored, sensed_at_m

#: What the log says of its last mission, interrupted: its name, ``goal``
#: (the start record's), the plan's step count, ``step`` (0-based) the first
#: step not known to have succeeded, ``started`` whether it had begun, and
#: ``localiser`` the localiser's last state (at that step's start, or after
#: the step before).
Interrupted = collections.namedtuple('Interrupted', 'mission goal steps step started localiser')
#: The mission to run: its name, goal and plan, where it starts
#: (executive :data:`Entry`), the localiser restored, and what to tell the operator.
Resume = collections.namedtuple('Resume', 'mission goal plan entry localiser message')


class CannotResume(ValueError):
    """The log's mission cannot be taken up; the message says why."""


def interrupted(records):
    """The log's last mission as an :data:`Interrupted`, or :class:`CannotResume`."""
    starts = [i for i, record in enumerate(records) if record.get('event') == 'start']
    if not starts:
        raise CannotResume('no mission in the log')
    start, mission = records[starts[-1]], records[starts[-1]:]
    name = start.get('mission', '?')
    end = next((record for record in mission if record.get('event') == 'end'), None)
    if end is not None:
        raise CannotResume('the last mission (%s) ended: %s (%s); nothing to resume'
                           % (name, end.get('status'), end.get('message')))
    if not start.get('goal') or start.get('localiser') is None:
        raise CannotResume('the log of mission %s does not say its goal and estimate: it cannot be resumed' % name)
    steps = [record for record in mission if record.get('event') in ('step', 'step_end')]
    last = steps[-1] if steps else None
    if last is None:
        step, started, localiser = int(start.get('first_step', 1)) - 1, False, start['localiser']
    else:
        step, started = int(last['step']) - (last['event'] == 'step'), last['event'] == 'step'
        localiser = last['localiser']
    return Interrupted(name, start['goal'], int(start['steps']), step, started, localiser)


def take_up(records, plan_of, settings, odometry_mm):
    """The :data:`Resume` of the log's interrupted mission (``records``:
    pirate.supervisory.mission_log.read), or :class:`CannotResume`.
    ``plan_of(goal)``: the goal's route plan (raises ValueError or
    yaml.YAMLError when it cannot be planned); ``settings``:
    config/supervisory.yaml; ``odometry_mm``: the robot's odometry now (None: unknown)."""
    found = interrupted(records)
    route_plan = _plan(found, plan_of)
    if odometry_mm is None:
        raise CannotResume('no robot state: the odometry, which the estimate goes on from, is not known')
    if found.step >= len(route_plan.steps):
        raise CannotResume('every step of mission %s had succeeded; nothing to resume' % found.mission)
    step = route_plan.steps[found.step]
    moved_mm = _moved_mm(found, step, settings, odometry_mm)
    try:
        localiser = restored(found.localiser, settings)
    except (KeyError, TypeError, ValueError) as bad:
        raise CannotResume('the log\'s estimate is not one (%s): it cannot be resumed' % bad)
    localiser.update(odometry_mm)
    entry = _entry(found, step, settings['robot'], moved_mm)
    return Resume(found.mission, found.goal, route_plan, entry, localiser,
                  _told(found, step, entry, localiser, moved_mm))


def _plan(found, plan_of):
    """The goal's plan again, the same length as the log's."""
    try:
        route_plan = plan_of(found.goal)
    except (ValueError, yaml.YAMLError) as refused:
        raise CannotResume('mission %s cannot be planned again: %s' % (found.mission, refused))
    if len(route_plan.steps) != found.steps:
        raise CannotResume('the map of mission %s now plans %d steps, the log\'s mission had %d: the map changed '
                           'since; start a new mission' % (found.mission, len(route_plan.steps), found.steps))
    return route_plan


def _moved_mm(found, step, settings, odometry_mm):
    """The odometry (mm) since the log's last estimate; :class:`CannotResume`
    when it is more than the step could have moved the robot."""
    then_mm = found.localiser.get('odometry_mm')
    moved_mm = 0.0 if then_mm is None else odometry_mm - float(then_mm)
    reach_mm = (abs(step.distance_mm) + abs(step.end_m - step.start_m) * 1000.0
                + settings['locate_tolerance_mm']) if found.started else settings['locate_tolerance_mm']
    if abs(moved_mm) > reach_mm:
        raise CannotResume('the odometry moved %.0f mm since the log\'s last estimate, more than step %d (%s) '
                           'could have moved the robot (%.0f mm): it was reset or the robot was moved; start a new '
                           'mission' % (moved_mm, found.step + 1, step.pab, reach_mm))
    return moved_mm


def _entry(found, step, robot, moved_mm):
    """Where the executive goes on: the step as after a pause if it had started."""
    if not found.started or step.junction is None:
        return Entry(found.step, found.started, False)
    if is_turn(step.junction.direction):
        return Entry(found.step, True, _may_have_sensed(found, step, robot, moved_mm))
    length_mm = (step.junction.exit_m - step.junction.entry_m) * 1000.0
    if abs(moved_mm) > length_mm:
        raise CannotResume('step %d (%s %s) had moved the robot %.0f mm when the executive stopped, more than %s\'s '
                           '%.0f mm: the crossing may have begun and cannot be resumed; the robot is held where it is'
                           % (found.step + 1, step.pab, step.option, moved_mm, step.junction.name, length_mm))
    return Entry(found.step, True, False)


def _may_have_sensed(found, step, robot, moved_mm):
    """A turn's step moved the robot as far as the earliest place where it
    could have sensed its junction (the map's place less the uncertainty at
    the step's start)."""
    sign = 1 if step.distance_mm > 0 else -1
    start_m = float(found.localiser['along_mm']) / 1000.0
    expected_m = sensed_at_m(step.junction, sign, robot)
    uncertainty_m = float(found.localiser['uncertainty_mm']) / 1000.0
    return sign * moved_mm / 1000.0 >= sign * (expected_m - start_m) - uncertainty_m


def _told(found, step, entry, localiser, moved_mm):
    """What the operator is told when the mission is taken up."""
    how = ('re-sent as it is: the turn may have begun' if entry.turn_begun else
           'run again from where the robot is' if entry.interrupted else 'not begun yet')
    return ('resuming mission %s from its log at step %d of %d (%s%s), %s; estimate %.0f mm along the map, within '
            '%.0f mm (the odometry moved %.0f mm since the log\'s last estimate)'
            % (found.mission, entry.step + 1, found.steps, step.pab, ' %s' % step.option if step.option else '',
               how, localiser.along_m * 1000.0, localiser.uncertainty_m(localiser.odometry_mm) * 1000.0, moved_mm))
