"""Start poses of the robot for a PAB, made with the robot's own motion primitives.

The clamp sweep (bench/pab_clamp_sweep) and probe (bench/pab_clamp_probe)
start Clamp Straight / Clamp Sideways from the poses the issue names;
each is made on a running :class:`pirate.testing.harness.SimHarness` the way
an operator or a cancelled goal would leave the robot, never by setting
the twin's state: a pose is something the robot can be in.
"""

from pirate.sequencer import clamp_state

CLAMP_STRAIGHT, CLAMP_SIDEWAYS, LEFT = 0, 1, 1     # Pirate.action goal names, option
PARTLY_RAD = -0.4       # Bend IV past this: the rear is half way to its clamp
TWIST_RAD = 0.5         # rotation of the twisted pose


def start_primitives(h, mm):
    """Motion primitives on the goal's guards, PLAY sent: for making a pose."""
    guards = h.server.book.for_diameter(mm)
    h.prims.use(guards)
    h.start_robot()
    return guards


def front_lifted(h, mm):
    """The front module up to the nominal lift of the robot's roll, then the safe hold."""
    guards = start_primitives(h, mm)
    h.prims.move_front(clamp_state.row_at(guards, 'move_front', h.feed.latest().orientation))
    h.prims.safe_hold()


def rear_partly_clamped(h, mm):
    """A Clamp Straight cancelled half way through its first (rear) clamp."""
    forget = h.when(lambda: h.feed.latest().angles['bend_iv'] < PARTLY_RAD, h.server.cancel)
    reason, outcome = h.execute(h.goal(CLAMP_STRAIGHT, pipe_diameter=mm))
    forget()
    if reason or outcome.status != 'preempted':
        raise RuntimeError('Clamp Straight not cancelled half way: %s' % (reason or outcome.message))


def both_clamped(h, mm):
    """Rear, then front custom-clamped where they lie (rows of each part's roll), then the safe hold."""
    guards = start_primitives(h, mm)
    for part, row in (('rear', 'clamp_rear_custom'), ('front', 'clamp_front_custom_first')):
        view = h.feed.latest()
        if part == 'front':         # as the clamp table does: the front module up before its V closes
            h.prims.move_front('move_front_first')
        h.prims.clamp(part, clamp_state.row_at(guards, row, clamp_state.part_roll(part, view.angles,
                                                                                    view.orientation)))
    h.prims.safe_hold()


def twisted(h, mm):
    """The free robot rotated to TWIST_RAD, then the safe hold (the rotation is not aligned)."""
    start_primitives(h, mm)
    h.prims.rotate(TWIST_RAD, name='twist')
    h.prims.safe_hold()


def clamped_by(name, option=0):
    """The pose a Clamp PAB leaves: the goal run to success."""
    def pose(h, mm):
        reason, outcome = h.execute(h.goal(name, pipe_diameter=mm, option=option))
        if reason or outcome.status != 'succeeded':
            raise RuntimeError(reason or outcome.message)
    return pose


#: Pose name -> callable(harness, pipe diameter mm); raises when the pose cannot be made.
#: The first five are the clamp sweep's (bench/pab_clamp_sweep); the clamped
#: ones are where Home most often starts.
POSES = {'straight': lambda h, mm: None, 'front lifted': front_lifted, 'rear partly clamped': rear_partly_clamped,
         'both clamped': both_clamped, 'twisted': twisted,
         'clamped straight': clamped_by(CLAMP_STRAIGHT), 'clamped left': clamped_by(CLAMP_SIDEWAYS, LEFT)}
CLAMP_SWEEP_POSES = ('straight', 'front lifted', 'rear partly clamped', 'both clamped', 'twisted')
