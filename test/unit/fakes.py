"""Fakes shared by the unit tests (no ROS)."""


class Wire(object):
    """A publisher that records the arrays it was asked to send."""

    def __init__(self):
        self.sent = []

    def publish(self, data):
        self.sent.append(list(data))
