#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Writes the seed corpora of the scene-file fuzz targets
# (tests/fuzz/corpus/scene_file_{obj,ply,gltf,glb}/) from Debian's
# assimp-testmodels (/usr/share/assimp/models/), and the list of where each
# seed came from (tests/fuzz/corpus/SCENE_SEEDS.md). Files are copied as
# they are, except that a glTF file's separate .bin buffer is put in the
# file itself (a base64 data URI in the .gltf, the binary chunk of a .glb):
# the fuzzer writes its input to one temporary file, next to which no .bin
# would be found. JSON of derived files is written compactly, to keep the
# inputs short. Usage: tests/fuzz/make_scene_seeds.py [MODELS_DIR]
import base64
import json
import os
import shutil
import struct
import sys

models = sys.argv[1] if len(sys.argv) > 1 else '/usr/share/assimp/models'
corpus = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'corpus')
gen = 'glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_'
origin = []


def out(fmt, name):
    d = os.path.join(corpus, 'scene_file_' + fmt)
    os.makedirs(d, exist_ok=True)
    return os.path.join(d, name)


def copy(fmt, src, name=None):
    name = name or os.path.basename(src)
    shutil.copyfile(os.path.join(models, src), out(fmt, name))
    origin.append((fmt, name, src, 'copied as it is'))


def with_buffer(src):
    gltf = json.load(open(os.path.join(models, src)))
    (buf,) = gltf['buffers']
    data = open(os.path.join(models, os.path.dirname(src), buf['uri']), 'rb').read()
    return gltf, buf, data


def embedded_gltf(src, name):
    gltf, buf, data = with_buffer(src)
    buf['uri'] = 'data:application/octet-stream;base64,' + base64.b64encode(data).decode()
    open(out('gltf', name), 'w').write(json.dumps(gltf, separators=(',', ':')))
    origin.append(('gltf', name, src, 'its .bin buffer as a data URI'))


def packed_glb(src, name):
    gltf, buf, data = with_buffer(src)
    del buf['uri']
    js = json.dumps(gltf, separators=(',', ':')).encode()
    js += b' ' * (-len(js) % 4)
    data += b'\0' * (-len(data) % 4)
    body = struct.pack('<II', len(js), 0x4E4F534A) + js + struct.pack('<II', len(data), 0x004E4942) + data
    open(out('glb', name), 'wb').write(struct.pack('<III', 0x46546C67, 2, 12 + len(body)) + body)
    origin.append(('glb', name, src, 'packed with its .bin buffer into a GLB'))


for f in ['box.obj', 'cube_with_vertexcolors.obj', 'number_formats.obj', 'testmixed.obj',
          'point_cloud.obj', 'concave_polygon.obj', 'regr_3429812.obj']:
    copy('obj', 'OBJ/' + f)
for f in ['cube.ply', 'cube_binary.ply', 'float-color.ply', 'points.ply', 'issue623.ply']:
    copy('ply', 'PLY/' + f)
copy('gltf', 'glTF2/simple_skin/simple_skin.gltf')
for n, what in [('01', 'lines'), ('05', 'fan'), ('06', 'triangles'), ('11', 'indexed-strip'),
                ('13', 'indexed-triangles'), ('14', 'byte-indices')]:
    embedded_gltf(gen + n + '.gltf', 'mode' + n + '-' + what + '.gltf')
embedded_gltf('glTF2/IndexOutOfRange/IndexOutOfRange.gltf', 'IndexOutOfRange.gltf')
copy('glb', 'glTF2/BoxBadNormals-glTF-Binary/BoxBadNormals.glb')
copy('glb', 'glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb')
for n, what in [('02', 'line-loop'), ('12', 'indexed-fan'), ('15', 'short-indices')]:
    packed_glb(gen + n + '.gltf', 'mode' + n + '-' + what + '.glb')

with open(os.path.join(corpus, 'SCENE_SEEDS.md'), 'w') as f:
    f.write('# Seeds of the scene-file fuzz targets\n\n'
            'Written by `tests/fuzz/make_scene_seeds.py` from Debian\'s assimp-testmodels '
            '(package `assimp-testmodels`, `/usr/share/assimp/models/`; the glTF-Asset-Generator '
            'models are MIT-licensed, see its LICENSE there). `scene_file_obj/cube.obj` and '
            '`huge.obj` are occu\'s own (a cube; a vertex beyond float range).\n\n'
            '| corpus | seed | from (under /usr/share/assimp/models/) | how |\n|---|---|---|---|\n')
    for fmt, name, src, how in origin:
        f.write('| scene_file_%s | %s | %s | %s |\n' % (fmt, name, src, how))
