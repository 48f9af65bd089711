#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Writes the seed corpus of the Quake III level fuzz target
# (tests/fuzz/corpus/scene_file_bsp/): small IBSP version 46 files made
# here, lump by lump (Kekoa Proudfoot's "Unofficial Quake 3 Map Specs"),
# each under the fuzzer's 4096 bytes, between them every face type
# (polygon, patch, mesh, billboard), every texture rule (drawn, nodraw,
# sky, translucent, water, fog, alpha-tested), a BSP tree of leaves in two
# clusters with and without visibility data, and spawn points.
# Usage: tests/fuzz/make_bsp_seeds.py
import os
import struct

corpus = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'corpus', 'scene_file_bsp')

SOLID, WATER, FOG, TRANS = 0x1, 0x20, 0x40, 0x20000000
SKY, NODRAW, ALPHASHADOW = 0x4, 0x80, 0x10000
UP, DOWN = (0, 0, 1), (0, 0, -1)


def level(textures, vertices, meshverts, faces, planes, nodes, leaves, leaf_faces, models, visdata, entities):
    """faces: (texture, type, vertex, n_vertices, meshvert, n_meshverts, normal, width, height)."""
    lumps = [b''] * 17
    lumps[0] = entities.encode() + b'\0'
    lumps[1] = b''.join(name.encode().ljust(64, b'\0') + struct.pack('<II', s, c) for name, s, c in textures)
    lumps[2] = b''.join(struct.pack('<4f', *p) for p in planes)
    lumps[3] = b''.join(struct.pack('<9i', *n) for n in nodes)
    lumps[4] = b''.join(struct.pack('<12i', *l) for l in leaves)
    lumps[5] = b''.join(struct.pack('<i', f) for f in leaf_faces)
    lumps[7] = b''.join(struct.pack('<6f4i', 0, 0, 0, 0, 0, 0, first, n, 0, 0) for first, n in models)
    lumps[10] = b''.join(struct.pack('<3f4f3f4B', *p, 0, 0, 0, 0, *n, 255, 255, 255, 255) for p, n in vertices)
    lumps[11] = b''.join(struct.pack('<i', m) for m in meshverts)
    lumps[13] = b''.join(struct.pack('<12i9f3f2i', t, -1, kind, v, nv, m, nm, -1, 0, 0, 0, 0, *([0.0] * 9), *normal, w, h)
                         for t, kind, v, nv, m, nm, normal, w, h in faces)
    lumps[16] = visdata
    out = b'IBSP' + struct.pack('<i', 46)
    at = 8 + 17 * 8
    for l in lumps:
        out += struct.pack('<ii', at, len(l))
        at += len(l)
    return out + b''.join(lumps)


def quad(z, normal):
    return [((0, 0, z), normal), ((64, 0, z), normal), ((64, 64, z), normal), ((0, 64, z), normal)]


def patch(width, height, heights):
    return [((64.0 * col / (width - 1), 64.0 * row / (height - 1), heights(row, col)), UP)
            for row in range(height) for col in range(width)]


SPAWNS = ('{\n"classname" "worldspawn"\n}\n'
          '{\n"classname" "info_player_deathmatch"\n"origin" "16 16 24"\n"angle" "90"\n}\n'
          '{\n"classname" "team_CTF_redspawn"\n"origin" "48 16 24"\n"angles" "0 270 0"\n}\n')
TWO_LEAVES = dict(planes=[(1, 0, 0, 32)],
                  nodes=[(0, -1, -2, 0, 0, 0, 64, 64, 64)],
                  leaves=[(0, 0, 32, 0, 0, 64, 64, 64, 0, 2, 0, 0), (1, 0, 0, 0, 0, 32, 64, 64, 2, 1, 0, 0)])
VIS = struct.pack('<ii', 2, 1) + bytes([0x1, 0x3])


def write(name, data):
    assert len(data) <= 4096, (name, len(data))
    os.makedirs(corpus, exist_ok=True)
    open(os.path.join(corpus, name), 'wb').write(data)


# Every face type: a floor polygon, a ceiling mesh triangle, a 3x3 patch,
# a flare billboard; nodraw, sky and glass polygons.
hump = [[0, 16, 0], [16, 64, 16], [0, 16, 0]]
write('all-face-types.bsp', level(
    textures=[('textures/test/wall', 0, SOLID), ('textures/common/nodraw', NODRAW, SOLID),
              ('textures/skies/sky', SKY, SOLID), ('textures/test/glass', 0, TRANS | SOLID), ('flareShader', 0, SOLID)],
    vertices=quad(0, UP) + [((0, 0, 64), DOWN), ((64, 0, 64), DOWN), ((0, 64, 64), DOWN)]
    + patch(3, 3, lambda r, c: hump[r][c]) + [((32, 32, 32), UP)],
    meshverts=[0, 2, 1, 0, 3, 2, 0, 1, 2],
    faces=[(0, 1, 0, 4, 0, 6, UP, 0, 0), (0, 3, 4, 3, 6, 3, DOWN, 0, 0), (0, 2, 7, 9, 0, 0, UP, 3, 3),
           (4, 4, 16, 1, 0, 0, UP, 0, 0), (1, 1, 0, 4, 0, 6, UP, 0, 0), (2, 1, 0, 4, 0, 6, UP, 0, 0),
           (3, 1, 0, 4, 0, 6, UP, 0, 0)],
    leaf_faces=[0, 1, 6], models=[(0, 7)], visdata=VIS, entities=SPAWNS, **TWO_LEAVES))

# A patch of two pieces by two (5x5 control points), on a floor; no
# visibility data (the compiler's -vis not run).
write('patch-5x5-no-vis.bsp', level(
    textures=[('textures/test/curve', 0, SOLID)],
    vertices=quad(0, UP) + patch(5, 5, lambda r, c: 32.0 * (r % 2) + 16.0 * (c % 2)),
    meshverts=[0, 2, 1, 0, 3, 2],
    faces=[(0, 1, 0, 4, 0, 6, UP, 0, 0), (0, 2, 4, 25, 0, 0, UP, 5, 5)],
    leaf_faces=[0, 1, 0], models=[(0, 2)], visdata=b'', entities=SPAWNS, **TWO_LEAVES))

# See-through textures: water, fog, an alpha-tested grate, and a solid
# wall; a brush entity (model 1) holding the grate.
write('see-through.bsp', level(
    textures=[('textures/test/wall', 0, SOLID), ('textures/liquids/water', 0, WATER | TRANS),
              ('textures/sfx/fog', NODRAW, FOG), ('textures/sfx/fogsurface', 0, FOG),
              ('textures/test/grate', ALPHASHADOW, SOLID)],
    vertices=quad(0, UP) + quad(16, UP) + quad(48, DOWN),
    meshverts=[0, 2, 1, 0, 3, 2],
    faces=[(0, 1, 0, 4, 0, 6, UP, 0, 0), (1, 1, 4, 4, 0, 6, UP, 0, 0), (2, 1, 4, 4, 0, 6, UP, 0, 0),
           (3, 1, 8, 4, 0, 6, DOWN, 0, 0), (4, 1, 8, 4, 0, 6, DOWN, 0, 0)],
    leaf_faces=[0, 1, 2, 3], models=[(0, 4), (4, 1)], visdata=VIS,
    entities=SPAWNS + '{\n"classname" "func_door"\n"model" "*1"\n}\n', **TWO_LEAVES))
