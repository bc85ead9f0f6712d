#!/usr/bin/env python3
"""Writes gen.py's parts with every random generator seeded anew: the random families (random
outlines, holes, prisms, jittered grids...) come out as other parts, the fixed ones as before.

  reseed.py DIR K    gen.py's parts into DIR, each random.Random(seed) seeded seed * 7919 + K

Session 19 meshed K = 1..6 in five poses (the parts that differ from K = 0: 228) to look for
counts that depend on the pose; run-stress.sh's checks apply to them the same way.
"""
import importlib.util
import os
import random
import sys

offset = int(sys.argv[2])
_Random = random.Random


class Reseeded(_Random):
    def __init__(self, seed=None):
        super().__init__(None if seed is None else seed * 7919 + offset)


random.Random = Reseeded  # before gen.py is loaded: its default arguments use it too
spec = importlib.util.spec_from_file_location(
    "gen", os.path.join(os.path.dirname(os.path.abspath(__file__)), "gen.py"))
gen = importlib.util.module_from_spec(spec)
spec.loader.exec_module(gen)
gen.gen(sys.argv[1])
