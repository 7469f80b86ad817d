#!/usr/bin/env python3
"""Writes parameters/shaken_block_record.csv, the synthetic acceleration record
that parameters/shaken_block.prm shakes its base with (run once; the CSV is
committed as data).

A recorded-like horizontal acceleration: a sum of 40 harmonics from 1 to
10 Hz with random phases (a fixed seed) and amplitudes falling as
1/sqrt(f),
under an envelope that builds up over 0.5 s, holds, then decays
exponentially: 4 s of shaking from model time 1 s (after the block has
settled on its joint), sampled every 0.005 s, scaled to a peak of 6 m/s^2
(0.61 g). Columns: time (s), acceleration (m/s^2).
"""

import math
import os
import random

START, DURATION, STEP, PEAK = 1.0, 4.0, 0.005, 6.0


def main():
    rng = random.Random(23)
    waves = []
    for k in range(40):
        f = 1.0 + 9.0 * k / 39.0
        waves.append((f, 1.0 / math.sqrt(f), rng.uniform(0.0, 2.0 * math.pi)))
    n = int(round(DURATION / STEP))
    times, values = [], []
    for i in range(n + 1):
        tau = i * STEP
        envelope = min(1.0, tau / 0.5) * (1.0 if tau < 1.5 else math.exp(-(tau - 1.5) / 0.8))
        # Zero at both ends: the record starts and ends at rest.
        envelope *= math.sin(math.pi * tau / DURATION) ** 0.25
        a = sum(amp * math.sin(2.0 * math.pi * f * tau + phase) for f, amp, phase in waves)
        times.append(START + tau)
        values.append(envelope * a)
    scale = PEAK / max(abs(v) for v in values)
    here = os.path.dirname(os.path.abspath(__file__))
    out = os.path.join(here, "..", "..", "parameters", "shaken_block_record.csv")
    with open(out, "w") as f:
        f.write("# Synthetic acceleration record (contrib/shaken_block/make_record.py)\n")
        f.write("time (s), acceleration (m/s^2)\n")
        for t, v in zip(times, values):
            f.write("%.3f, %.6f\n" % (t, v * scale))


if __name__ == "__main__":
    main()
