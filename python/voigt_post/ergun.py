"""Ergun's pressure gradient through a rigid bed of spheres (Ergun 1952; the paper's Eq. 23) and
what it takes from the porous bed's scene: the gas (the scene's fluid), the inflow velocity at
y = 0, gravity, and the spheres' diameter from the packing's record (packing.json, input).
Standard library only.

    from voigt_post import ergun, scene_record
    p = ergun.bed_flow(scene_record.scene(run), "cases/porous_bed/packing.json")
    ergun.gradient(0.4, **p)     # Pa/m; p also holds g (m/s^2), for the gas's rho g
"""
import json

from . import scene_record


def gradient(e, rho, mu, u, d, **_):
    """-dp/dy (Pa/m) of a rigid bed of voidage e: gas density rho, viscosity mu, superficial
    velocity u, sphere diameter d (paper Eq. 23)."""
    return (1 - e) / e ** 3 * rho * u ** 2 / d * (150 * (1 - e) * mu / (d * u * rho) + 1.75)


def bed_flow(scene, packing_json):
    """{rho, mu, u, d, g} of a porous-bed scene (a dict: a run's record or the case's file) and
    its packing record: the fluid's density and viscosity, the y- inflow's velocity, the
    spheres' diameter, and g = -gravity_y (0 without gravity)."""
    gas = scene_record.material(scene)
    with open(packing_json) as f:
        d = json.load(f)["input"]["diameter"]
    gravity = scene.get("gravity") or [0, 0, 0]
    return {"rho": float(gas["density"]), "mu": float(gas["viscosity"]),
            "u": float(scene["boundaries"]["y-"]["velocity"][1]), "d": float(d), "g": -float(gravity[1])}
