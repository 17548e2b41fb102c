#!/usr/bin/env python3
"""Write a scene with N soft spheres in a liquid, as N level sets or as one (their union).

  spheres.py N {many|one} > scene.yaml

The cost study of several level sets (perf/level_sets/README.md): 48^3 cells, spheres of
radius 4 cells on a lattice, at rest under gravity; `run` times 30 steps of each.
"""
import sys

n, mode = int(sys.argv[1]), sys.argv[2]
centres = []
for q in range(n):  # a 2 x 2 x 2 lattice, filled in order
    i, j, k = q % 2, (q // 2) % 2, q // 4
    centres.append([0.3 + 0.4 * i, 0.3 + 0.4 * j, 0.3 + 0.4 * k])
print("""name: spheres_%d_%s
domain: {lo: [0, 0, 0], hi: [1, 1, 1], cells: [48, 48, 48]}
boundaries: {default: {type: no_slip}}
time: {end: 1, cfl: 0.5}
materials:
  liquid: {density: 1000, viscosity: 0.01}
  rubber: {density: 1200, shear_modulus: 1000}
fluid: liquid
gravity: [0, -9.81, 0]
effects: [navier_stokes, gravity, level_set, reinit, elasticity]""" % (n, mode))
sph = ["{type: sphere, center: [%g, %g, %g], radius: 0.0833}" % tuple(c) for c in centres]
if mode == "many":
    print("level_sets:")
    for q, s in enumerate(sph):
        print("  - {name: s%d, phase: rubber, shape: %s}" % (q, s))
    print("elasticity: {level_set: [%s]}" % ", ".join("s%d" % q for q in range(n)))
else:
    shape = sph[0] if n == 1 else "{type: union, of: [%s]}" % ", ".join(sph)
    print("level_set: {phase: rubber, shape: %s}" % shape)
    print("elasticity: {}")
