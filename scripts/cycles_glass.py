"""Glass made by a third-party tool (Blender), to check the reference's refraction against
another path tracer's: a clear glass block and a glass sphere, each the boundary of a volume
(Principled BSDF, transmission 1, roughness 0, IOR 1.5; KHR_materials_volume through the
exporter's "glTF Material Output" thickness), in front of a wall of emissive stripes, in the
dark. The stripes seen through the glass are displaced and mirrored by refraction and total
internal reflection, so any difference in either shows. A development check, not a CI
dependency (Debian's blender and, for its glTF exporter, python3-numpy).

    blender -b --python scripts/cycles_glass.py -- OUT_DIR [--render SPP] [--size WxH]

writes OUT_DIR/glass.gltf (+ .bin) and, with --render, OUT_DIR/cycles_SPP.exr (linear radiance,
one-pixel box filter, no clamping) to hold against
`twinlight render --scene OUT_DIR/glass.gltf --path reference --sky 0 --camera 0`.
"""
import math
import os
import sys

import bpy

sys.path.append(os.path.dirname(os.path.abspath(__file__)))
from cycles_common import export_triangles, render_exr  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
out_dir = argv[0] if argv else "out/glass"
render_spp = int(argv[argv.index("--render") + 1]) if "--render" in argv else 0
size = argv[argv.index("--size") + 1] if "--size" in argv else "160x120"
width, height = (int(v) for v in size.split("x"))

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene


def emissive(name, strength):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    bsdf.inputs["Specular"].default_value = 0.0
    bsdf.inputs["Emission"].default_value = (1.0, 1.0, 1.0, 1.0)
    bsdf.inputs["Emission Strength"].default_value = strength
    return m


def glass(name, thickness):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nodes = m.node_tree.nodes
    bsdf = nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    bsdf.inputs["Roughness"].default_value = 0.0
    bsdf.inputs["Transmission"].default_value = 1.0
    bsdf.inputs["IOR"].default_value = 1.5
    # The exporter reads KHR_materials_volume's thickness from a node group of this name.
    group = bpy.data.node_groups.get("glTF Material Output") or bpy.data.node_groups.new("glTF Material Output",
                                                                                         "ShaderNodeTree")
    if "Thickness" not in group.inputs:
        group.inputs.new("NodeSocketFloat", "Thickness")
    node = nodes.new("ShaderNodeGroup")
    node.node_tree = group
    node.inputs["Thickness"].default_value = thickness
    return m


bright, dim, clear = emissive("stripe_bright", 1.0), emissive("stripe_dim", 0.15), glass("clear_glass", 0.8)
for i in range(12):  # vertical stripes 0.35 m wide on a wall 2 m behind the glass
    bpy.ops.mesh.primitive_plane_add(size=1.0, location=(-2.1 + 0.35 * i + 0.175, 2.0, 0.9), rotation=(math.pi / 2, 0, 0))
    o = bpy.context.object
    o.scale = (0.35, 2.4, 1.0)
    o.data.materials.append(bright if i % 2 == 0 else dim)
bpy.ops.mesh.primitive_cube_add(size=1.0, location=(-0.55, 0.0, 0.7), rotation=(0, 0, math.radians(30)))
block = bpy.context.object
block.scale = (0.8, 0.8, 1.2)
block.data.materials.append(clear)
bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=0.45, location=(0.75, -0.2, 0.8))
sphere = bpy.context.object
bpy.ops.object.shade_smooth()
sphere.data.materials.append(clear)

bpy.ops.object.camera_add(location=(0.0, -4.0, 0.8), rotation=(math.pi / 2, 0, 0))
camera = bpy.context.object
camera.data.sensor_fit = "VERTICAL"
camera.data.angle = math.radians(30.0)
scene.camera = camera
scene.render.resolution_x, scene.render.resolution_y = width, height

print(f"glass: written to {export_triangles(scene, out_dir, 'glass')}")

if render_spp:
    # Cycles with Twinlight's definitions: the stripes pure emission (a radiance on both faces),
    # a black world, a one-pixel box filter, no clamping, enough bounces for the glass.
    for m in (bright, dim):
        nodes, links = m.node_tree.nodes, m.node_tree.links
        emission = nodes.new("ShaderNodeEmission")
        emission.inputs["Strength"].default_value = nodes["Principled BSDF"].inputs["Emission Strength"].default_value
        links.new(emission.outputs[0], nodes["Material Output"].inputs["Surface"])
    render_exr(scene, render_spp, 64, os.path.join(out_dir, f"cycles_{render_spp}.exr"))
