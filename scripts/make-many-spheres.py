#!/usr/bin/env python3
"""Writes assets/scenes/many_spheres.toml: the final scene of "Ray Tracing in
One Weekend" (Shirley) redone for Whitted shading: a grid of small spheres
with random materials on a checkered floor, and three big ones (glass,
diffuse, mirror). Deterministic (fixed seed), so the file is reproducible."""
import random
from pathlib import Path

random.seed(1980)
palette = {
    "red": [0.8, 0.15, 0.1], "orange": [0.9, 0.5, 0.1], "yellow": [0.9, 0.8, 0.2],
    "green": [0.2, 0.7, 0.25], "teal": [0.1, 0.6, 0.6], "blue": [0.15, 0.3, 0.85],
    "purple": [0.55, 0.2, 0.7], "pink": [0.9, 0.45, 0.6],
}
out = ['''# Hundreds of spheres, in the spirit of the final scene of Peter Shirley's
# "Ray Tracing in One Weekend": small spheres of random materials on a grid,
# three big ones in the middle. Made by scripts/make-many-spheres.py (fixed
# seed). With this many shapes the bounding volume hierarchy matters.

[render]
max_depth = 5
background = [0.6, 0.75, 0.95]
ambient = [0.2, 0.2, 0.22]

[camera]
from = [13, 2, 3]
to = [0, 0, 0]
fov = 20

[[lights]]
position = [10, 20, 10]
intensity = 0.7

[[lights]]
position = [-10, 12, 4]
intensity = 0.3

[materials.floor]
color = [0.85, 0.85, 0.8]
checker = { color = [0.3, 0.35, 0.3], size = 1.0 }

[materials.glass]
color = [1, 1, 1]
diffuse = 0.0
specular = 0.7
shininess = 300
transparency = 0.95
ior = 1.5

[materials.metal]
color = [0.85, 0.8, 0.7]
diffuse = 0.1
specular = 0.6
shininess = 200
mirror = 0.8

[materials.brown]
color = [0.4, 0.2, 0.1]
specular = 0.2
shininess = 30
''']
for name, c in palette.items():
    out.append(f'''
[materials.{name}]
color = {c}
specular = 0.3
shininess = 50
''')
out.append('''
[[planes]]
point = [0, 0, 0]
normal = [0, 1, 0]
material = "floor"
''')
count = 0
for a in range(-11, 11):
    for b in range(-11, 11):
        x, z = a + 0.9 * random.random(), b + 0.9 * random.random()
        if (x - 4) ** 2 + z ** 2 < 0.81 or x ** 2 + z ** 2 < 0.81 or (x + 4) ** 2 + z ** 2 < 0.81:
            continue
        roll = random.random()
        material = "glass" if roll > 0.92 else "metal" if roll > 0.78 else random.choice(list(palette))
        out.append(f'''
[[spheres]]
center = [{x:.3f}, 0.2, {z:.3f}]
radius = 0.2
material = "{material}"
''')
        count += 1
for center, material in [([0, 1, 0], "glass"), ([-4, 1, 0], "brown"), ([4, 1, 0], "metal")]:
    out.append(f'''
[[spheres]]
center = {center}
radius = 1
material = "{material}"
''')
Path(__file__).resolve().parent.parent.joinpath("assets/scenes/many_spheres.toml").write_text("".join(out))
print(f"{count + 3} spheres")
