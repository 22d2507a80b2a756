"""actionlib's ActionServer without its error for a goal cancelled before it arrived.

A cancel that reaches the server before its goal (they travel on two topics)
leaves a record with the goal's id and no goal in actionlib's status list;
when the goal comes it is recalled there. Every later cancel that matches
the record (the same id again, a cancel-all, a cancel before a time) made
actionlib build a goal handle on it and log "Attempt to get a goal id on an
uninitialized ServerGoalHandle" twice while deciding that nothing was to be
cancelled: goal/cancel storms logged hundreds of errors. Here such a cancel
passes the goal-less records by, which is what actionlib ends up doing.
"""
import actionlib


class QuietActionServer(actionlib.ActionServer):
    """An ActionServer whose cancels skip goal-less records (module docstring)."""

    def internal_cancel_callback(self, goal_id):
        with self.lock:
            goalless = [tracker for tracker in self.status_list if tracker.goal is None]
            self.status_list[:] = [tracker for tracker in self.status_list if tracker.goal is not None]
            try:
                super(QuietActionServer, self).internal_cancel_callback(goal_id)
            finally:
                known = set(tracker.status.goal_id.id for tracker in goalless)
                self.status_list[:] = goalless + [tracker for tracker in self.status_list
                                                  if tracker.goal is not None or tracker.status.goal_id.id not in known]
