"""The passive drop: the part let go at a feeder's entry and simulated with the dynamic level
(Eq. 7) until it rests or leaves (``passive``, with Eq. 10's objective), and its pictures, a
snapshot strip and an animation (``pictures``). Design verdicts and optimisation built on the
drop belong here."""
