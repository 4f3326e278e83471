"""A Cornell-style box lit only by an emissive ceiling panel, made by a third-party tool (Blender)
so that the reference's emitter sampling is checked on content it did not write: the box as
glTF (Blender's exporter), and optionally Cycles' image of it for a development check of the
reference (not a CI dependency).

    blender -b --python scripts/cycles_panel_box.py -- OUT_DIR [--render SPP] [--size WxH]

writes OUT_DIR/panel_box.gltf (+ .bin) and, with --render, OUT_DIR/cycles_SPP.exr (linear
radiance, box filter of one pixel, no clamping, diffuse materials) to hold against
`twinlight render --scene OUT_DIR/panel_box.gltf --path reference --materials diffuse --sky 0`.

The box is 2 x 2 x 2 m with white (0.73), red and green walls subdivided into 40 x 40 quads, two
blocks, and a 0.6 x 0.5 m panel of 128 triangles emitting 12 (warm white) 1 mm under the
ceiling; about 16,700 triangles in all. Definitions as Twinlight's (docs/accuracy.md): emission
is a radiance on both faces, surfaces are Lambertian in the diffuse material mode, no sky.
"""
import math
import os
import sys

import bpy

sys.path.append(os.path.dirname(os.path.abspath(__file__)))
from cycles_common import export_triangles, render_exr  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
out_dir = argv[0] if argv else "out/panel_box"
render_spp = int(argv[argv.index("--render") + 1]) if "--render" in argv else 0
size = argv[argv.index("--size") + 1] if "--size" in argv else "256x192"
width, height = (int(v) for v in size.split("x"))

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene


def material(name, colour, emission=None, strength=0.0):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*colour, 1.0)
    bsdf.inputs["Roughness"].default_value = 1.0
    bsdf.inputs["Specular"].default_value = 0.5
    if emission:
        bsdf.inputs["Emission"].default_value = (*emission, 1.0)
        bsdf.inputs["Emission Strength"].default_value = strength
    return m


white = material("white", (0.73, 0.73, 0.73))
red = material("red", (0.63, 0.065, 0.05))
green = material("green", (0.14, 0.45, 0.091))
light = material("panel", (0.78, 0.78, 0.78), (1.0, 0.85, 0.6), 12.0)


def wall(name, location, rotation, mat, cuts=39, size=2.0):
    bpy.ops.mesh.primitive_grid_add(x_subdivisions=cuts + 1, y_subdivisions=cuts + 1, size=size, location=location,
                                    rotation=rotation)
    o = bpy.context.object
    o.name = name
    o.data.materials.append(mat)
    return o


half = math.pi / 2
wall("floor", (0, 0, 0), (0, 0, 0), white)
wall("ceiling", (0, 0, 2), (math.pi, 0, 0), white)
wall("back", (0, 1, 1), (half, 0, 0), white)  # Blender is Z up; the exporter turns it Y up
wall("left_red", (-1, 0, 1), (0, half, 0), red)
wall("right_green", (1, 0, 1), (0, -half, 0), green)
panel = wall("panel", (0, 0, 1.999), (math.pi, 0, 0), light, cuts=7, size=1.0)
panel.scale = (0.6, 0.5, 1.0)


def block(name, location, dimensions, angle):
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=location, rotation=(0, 0, angle))
    o = bpy.context.object
    o.name = name
    o.scale = dimensions
    o.data.materials.append(white)
    return o


block("tall_block", (-0.35, 0.3, 0.6), (0.6, 0.6, 1.2), math.radians(18))
block("short_block", (0.35, -0.35, 0.3), (0.6, 0.6, 0.6), math.radians(-17))

bpy.ops.object.camera_add(location=(0, -3.9, 1.0), rotation=(half, 0, 0))
camera = bpy.context.object
camera.data.sensor_fit = "VERTICAL"
camera.data.angle = math.radians(38.6)
scene.camera = camera
scene.render.resolution_x, scene.render.resolution_y = width, height

export_triangles(scene, out_dir, "panel_box")
triangles = sum(len(o.data.polygons) for o in scene.objects if o.type == "MESH")
print(f"panel_box: {triangles} triangles, written to {out_dir}/panel_box.gltf")

if render_spp:
    # Cycles with Twinlight's definitions: Lambertian surfaces of the same base colour, the
    # panel's emission a radiance on both faces, a black world, a one-pixel box filter, no
    # clamping, enough bounces that Russian roulette ends the paths.
    for m in (white, red, green, light):
        nodes, links = m.node_tree.nodes, m.node_tree.links
        principled = nodes["Principled BSDF"]
        diffuse = nodes.new("ShaderNodeBsdfDiffuse")
        diffuse.inputs["Color"].default_value = principled.inputs["Base Color"].default_value
        out = nodes["Material Output"]
        strength = principled.inputs["Emission Strength"].default_value
        if strength > 0.0:
            emission = nodes.new("ShaderNodeEmission")
            emission.inputs["Color"].default_value = principled.inputs["Emission"].default_value
            emission.inputs["Strength"].default_value = strength
            add = nodes.new("ShaderNodeAddShader")
            links.new(diffuse.outputs[0], add.inputs[0])
            links.new(emission.outputs[0], add.inputs[1])
            links.new(add.outputs[0], out.inputs["Surface"])
        else:
            links.new(diffuse.outputs[0], out.inputs["Surface"])
    render_exr(scene, render_spp, 128, os.path.join(out_dir, f"cycles_{render_spp}.exr"))
