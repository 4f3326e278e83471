"""What the Blender development checks (scripts/cycles_*.py) share: the scene as Twinlight
reads it (triangles, exported as glTF) and Cycles set to Twinlight's definitions (a black world,
a one-pixel box filter, no clamping, no denoising, enough bounces that paths end by Russian
roulette, linear radiance in a 32-bit EXR). Imported by those scripts from their folder."""
import os

import bpy


def export_triangles(scene, out_dir, name):
    """Triangulates every mesh (so Twinlight and Cycles see the same triangles) and writes
    OUT_DIR/NAME.gltf (+ .bin) with the cameras."""
    for o in scene.objects:
        if o.type == "MESH":
            bpy.context.view_layer.objects.active = o
            mod = o.modifiers.new("triangulate", "TRIANGULATE")
            bpy.ops.object.modifier_apply(modifier=mod.name)
    os.makedirs(out_dir, exist_ok=True)
    path = os.path.join(out_dir, f"{name}.gltf")
    bpy.ops.export_scene.gltf(filepath=path, export_format="GLTF_SEPARATE", export_cameras=True, export_lights=False,
                              export_apply=True)
    return path


def render_exr(scene, spp, bounces, path):
    """Renders the scene's camera with Cycles on the CPU at `spp` samples into the EXR `path`."""
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = spp
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.max_bounces = c.diffuse_bounces = c.glossy_bounces = c.transmission_bounces = bounces
    c.volume_bounces = c.transparent_max_bounces = bounces
    c.sample_clamp_direct = c.sample_clamp_indirect = 0.0
    c.caustics_reflective = c.caustics_refractive = True
    c.blur_glossy = 0.0
    c.filter_type = "BOX"
    c.filter_width = 1.0
    c.seed = 1
    scene.view_settings.view_transform = "Standard"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    print(f"wrote {path}")
