"""A lossy RS485 bus between the simulated robot and its state assembler:
for tests and bench/faults only."""

#: What the fault campaign injected: 10 % of Small States dropped, each delayed 0-80 ms.
LOSS, JITTER_S = 0.1, 0.08
#: s a cycle's replies are sent before the state node checks them (half the Mega's 0.1 s cycle).
SENT_BEFORE_S = 0.05


class LossyBus(object):
    """Wraps an assembler's ``update(board, data, now)``: each reply of a
    cycle checked at ``now`` was sent :data:`SENT_BEFORE_S` before, is lost
    with ``loss`` or arrives 0-``jitter_s`` after it was sent; one arriving
    after the check waits for the next cycle's (as the state node's checks
    fall between arrivals). ``rng``: a seeded :class:`random.Random`."""

    def __init__(self, update, rng, loss=LOSS, jitter_s=JITTER_S):
        self.update, self.rng, self.loss, self.jitter_s = update, rng, loss, jitter_s
        self.late = []

    def __call__(self, board, data, now):
        for arrival, late_board, late_data in [m for m in self.late if m[0] <= now]:
            self.update(late_board, late_data, arrival)
        self.late = [m for m in self.late if m[0] > now]
        if self.rng.random() < self.loss:
            return False
        arrival = now - SENT_BEFORE_S + self.rng.uniform(0.0, self.jitter_s)
        if arrival > now:
            self.late.append((arrival, board, data))
            return False
        return self.update(board, data, arrival)
