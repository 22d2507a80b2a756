"""Where the robot is along its pipe, for RViz (pure).

The base frame stands on the pipe's axis (x, the robot's forward) at the
robot's odometry, so the model travels through the drawn pipe as the
wheels turn. The pipe drawn follows the robot, a stretch of it centred on
the ring mark nearest the robot; the stretch carries a ring every
:data:`RING_SPACING_MM` and a label every :data:`LABEL_SPACING_MM`, fixed
in the pipe frame, so the rings stream past a travelling robot. A text
beside the robot says what it senses: its odometry and, while a mission
publishes one, the estimate along the map and how far it may be off.
No ROS import here.
"""
import math

RING_SPACING_MM = 100      # a ring mark on the drawn pipe every 100 mm
LABEL_SPACING_MM = 1000    # a distance label every metre
RING_SEGMENTS = 24         # straight pieces a drawn ring is made of
ESTIMATE_MAX_AGE_S = 2.0   # a mission's estimate older than this is not shown (it publishes at 5 Hz)


def _finite(name, value):
    if not math.isfinite(value):
        raise ValueError('%s %r is not finite' % (name, value))
    return value


def base_along_m(odometry_mm):
    """x (m) of the base frame along the pipe for an odometry (mm)."""
    return _finite('odometry', odometry_mm) / 1000.0


def stretch_centre_mm(odometry_mm):
    """x (mm) the drawn stretch of pipe is centred on: the nearest ring mark."""
    return RING_SPACING_MM * round(_finite('odometry', odometry_mm) / RING_SPACING_MM)


def ring_marks_mm(centre_mm, length_mm):
    """x (mm) of every ring mark on a stretch ``length_mm`` long centred on ``centre_mm``."""
    first = int(math.ceil((centre_mm - length_mm / 2.0) / RING_SPACING_MM))
    last = int(math.floor((centre_mm + length_mm / 2.0) / RING_SPACING_MM))
    return [k * RING_SPACING_MM for k in range(first, last + 1)]


def metre_labels(marks_mm):
    """[(x mm, text)] of the ring marks that carry a distance label."""
    return [(x, '%d m' % (x // LABEL_SPACING_MM)) for x in marks_mm if x % LABEL_SPACING_MM == 0]


def ring_segments(x_m, radius_m):
    """Point pairs ((x, y, z), (x, y, z)) m drawing a ring round the axis at ``x_m``."""
    points = [(x_m, radius_m * math.cos(2 * math.pi * k / RING_SEGMENTS),
               radius_m * math.sin(2 * math.pi * k / RING_SEGMENTS)) for k in range(RING_SEGMENTS)]
    return [(points[k], points[(k + 1) % RING_SEGMENTS]) for k in range(RING_SEGMENTS)]


def position_text(odometry_mm, along_mm=None, uncertainty_mm=None):
    """The text beside the robot: its odometry, and the mission's estimate if any.

    RViz's text font has ASCII only, so the spread reads "+/-".
    """
    lines = ['odometry %d mm' % round(_finite('odometry', odometry_mm))]
    if along_mm is not None and math.isfinite(along_mm):
        estimate = 'along the map %d mm' % round(along_mm)
        if uncertainty_mm is not None and math.isfinite(uncertainty_mm):
            estimate += ' +/- %d mm' % round(uncertainty_mm)
        lines.append(estimate)
    return '\n'.join(lines)


class MissionEstimate(object):
    """The latest estimate along the map (mm) and its spread, with when each came (s)."""

    def __init__(self, max_age_s=ESTIMATE_MAX_AGE_S):
        self.max_age_s = max_age_s
        self.along_mm = self.uncertainty_mm = None
        self.along_at_s = self.uncertainty_at_s = None

    def heard_along(self, along_mm, now_s):
        self.along_mm, self.along_at_s = along_mm, now_s

    def heard_uncertainty(self, uncertainty_mm, now_s):
        self.uncertainty_mm, self.uncertainty_at_s = uncertainty_mm, now_s

    def current(self, now_s):
        """(along mm, uncertainty mm) heard within the max age; None for either that is not."""
        return (self._fresh(self.along_mm, self.along_at_s, now_s),
                self._fresh(self.uncertainty_mm, self.uncertainty_at_s, now_s))

    def _fresh(self, value, at_s, now_s):
        if at_s is None or not 0.0 <= now_s - at_s <= self.max_age_s:
            return None
        return value
