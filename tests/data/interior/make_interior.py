"""Builds the small interior of issue 49 in Blender and exports it as glTF,
as a user would (File > Export > glTF 2.0, lamps included), and renders it
with Cycles as the stored reference. Run once, with Debian's Blender 3.4:

  blender -b --factory-startup --python tests/data/interior/make_interior.py -- OUT_DIR [SAMPLES]

OUT_DIR gets interior.glb, moving.glb (the ball rolls), and three Cycles renders: cycles.exr (the
Principled materials as exported), cycles-no-specular.exr (every Principled
specular at 0) and cycles-lambert.exr (the metallic-0 materials as Cycles'
Lambertian Diffuse BSDF, as igi reads them), with their means in cycles.json.

The room: 4 x 3 m, 2.5 m high, a window in the -y wall that a 3 W/m^2 sun
shines through, a 40 W point lamp under the ceiling, an emissive panel of
strength 10 on the -x wall, a white box, a rough metal ball and a checker
texture on the floor. The world is black: only the lamps light it.
"""
import json
import math
import os
import sys
import time

import bpy

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
out_dir = os.path.abspath(argv[0] if argv else ".")
samples = int(argv[1]) if len(argv) > 1 else 1024
os.makedirs(out_dir, exist_ok=True)

bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene


def material(name, colour, metallic=0.0, roughness=0.5, emission=None, strength=0.0, texture=None):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*colour, 1.0)
    bsdf.inputs["Metallic"].default_value = metallic
    bsdf.inputs["Roughness"].default_value = roughness
    if emission is not None:
        bsdf.inputs["Emission"].default_value = (*emission, 1.0)
        bsdf.inputs["Emission Strength"].default_value = strength
    if texture is not None:
        node = m.node_tree.nodes.new("ShaderNodeTexImage")
        node.image = texture
        m.node_tree.links.new(node.outputs["Color"], bsdf.inputs["Base Color"])
    return m


def checker(name, size=64, squares=8):
    image = bpy.data.images.new(name, size, size)
    pixels = []
    for y in range(size):
        for x in range(size):
            light = ((x * squares // size) + (y * squares // size)) % 2 == 0
            c = (0.8, 0.75, 0.7) if light else (0.3, 0.25, 0.2)  # sRGB-encoded texels
            pixels += [*c, 1.0]
    image.pixels = pixels
    image.filepath_raw = os.path.join(out_dir, name + ".png")
    image.file_format = "PNG"
    image.save()
    return image


def quad(name, corners, mat):
    """A one-sided quad from four corners, counter-clockwise seen from its front."""
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(corners, [], [(0, 1, 2, 3)])
    if len(corners) == 4:
        mesh.uv_layers.new(name="UVMap")
        uv = mesh.uv_layers[0].data
        for i, c in enumerate([(0, 0), (1, 0), (1, 1), (0, 1)]):
            uv[i].uv = (c[0] * 4, c[1] * 3)
    mesh.materials.append(mat)
    obj = bpy.data.objects.new(name, mesh)
    scene.collection.objects.link(obj)
    return obj


W, D, H = 4.0, 3.0, 2.5  # x from 0 to W, y from 0 to D, z from 0 to H
white = material("walls", (0.7, 0.7, 0.7), roughness=0.8)
floor = material("floor", (1, 1, 1), roughness=0.8, texture=checker("checker"))
# Facing into the room.
quad("floor", [(0, 0, 0), (W, 0, 0), (W, D, 0), (0, D, 0)], floor)
quad("ceiling", [(0, 0, H), (0, D, H), (W, D, H), (W, 0, H)], white)
quad("wall +y", [(0, D, 0), (W, D, 0), (W, D, H), (0, D, H)], white)
quad("wall -x", [(0, 0, 0), (0, D, 0), (0, D, H), (0, 0, H)], white)
quad("wall +x", [(W, 0, 0), (W, 0, H), (W, D, H), (W, D, 0)], white)
# The -y wall around a window from x 1.2 to 2.8, z 0.9 to 2.0.
x0, x1, z0, z1 = 1.2, 2.8, 0.9, 2.0
for name, (a, b, c, d) in {"below": (0, W, 0, z0), "above": (0, W, z1, H), "left": (0, x0, z0, z1),
                           "right": (x1, W, z0, z1)}.items():
    quad("wall -y " + name, [(a, 0, c), (a, 0, d), (b, 0, d), (b, 0, c)], white)

bpy.ops.mesh.primitive_cube_add(size=0.8, location=(2.5, 1.1, 0.4))
bpy.context.object.data.materials.append(material("box", (0.8, 0.8, 0.8), roughness=0.8))
bpy.ops.mesh.primitive_uv_sphere_add(radius=0.4, location=(1.4, 1.9, 0.4), segments=48, ring_count=24)
bpy.ops.object.shade_smooth()
ball = bpy.context.object
bpy.context.object.data.materials.append(material("metal", (0.9, 0.8, 0.6), metallic=1.0, roughness=0.3))
panel = material("panel", (0, 0, 0), roughness=1.0, emission=(1.0, 0.9, 0.8), strength=10.0)
quad("panel", [(0.01, 1.2, 1.3), (0.01, 1.8, 1.3), (0.01, 1.8, 1.7), (0.01, 1.2, 1.7)], panel)  # on the -x wall

point = bpy.data.lights.new("lamp", "POINT")
point.energy = 40.0  # W
point.shadow_soft_size = 0.0
point.color = (1.0, 0.95, 0.85)
lamp = bpy.data.objects.new("lamp", point)
lamp.location = (2.0, 1.6, 2.2)
scene.collection.objects.link(lamp)
sun = bpy.data.lights.new("sun", "SUN")
sun.energy = 3.0  # W/m^2
sun.angle = 0.0
sun_obj = bpy.data.objects.new("sun", sun)
sun_obj.rotation_euler = (math.radians(55), 0.0, math.radians(-20))  # down through the -y window, into the room
scene.collection.objects.link(sun_obj)

cam = bpy.data.cameras.new("camera")
cam.lens = 20.0
camera = bpy.data.objects.new("camera", cam)
camera.location = (3.7, 2.85, 1.6)
camera.rotation_euler = (math.radians(76), 0.0, math.radians(130))  # towards -x, -y (the window), a little down
scene.collection.objects.link(camera)
scene.camera = camera

world = bpy.data.worlds.new("black")
world.use_nodes = True
world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
scene.world = world

scene.render.resolution_x, scene.render.resolution_y = 160, 120
scene.render.resolution_percentage = 100
bpy.ops.export_scene.gltf(filepath=os.path.join(out_dir, "interior.glb"), export_format="GLB",
                          export_lights=True, export_cameras=True, export_apply=True)

# moving.glb: the same room, the ball rolling 1.2 m along +x in 2 s (frames 1 to 49 at 24 fps).
scene.render.fps = 24
ball.keyframe_insert("location", frame=1)
ball.location.x += 1.2
ball.keyframe_insert("location", frame=49)
ball.location.x -= 1.2
scene.frame_set(1)
bpy.ops.export_scene.gltf(filepath=os.path.join(out_dir, "moving.glb"), export_format="GLB",
                          export_lights=True, export_cameras=True, export_apply=True, export_animations=True)

scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = samples
scene.cycles.use_denoising = False
scene.cycles.max_bounces = 64
scene.cycles.diffuse_bounces = scene.cycles.glossy_bounces = 64
scene.cycles.sample_clamp_direct = scene.cycles.sample_clamp_indirect = 0.0
scene.cycles.caustics_reflective = scene.cycles.caustics_refractive = True
scene.cycles.filter_width = 0.01  # box-like: one pixel's rays
scene.view_settings.view_transform = "Standard"
scene.render.image_settings.file_format = "OPEN_EXR"
scene.render.image_settings.color_depth = "16"  # half floats: the means need no more


def render(name):
    scene.render.filepath = os.path.join(out_dir, name)
    start = time.time()
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(scene.render.filepath)
    px = list(image.pixels)
    n = len(px) // 4
    mean = [sum(px[c::4]) / n for c in range(3)]
    return {"mean": mean, "luminance": 0.2126 * mean[0] + 0.7152 * mean[1] + 0.0722 * mean[2],
            "seconds": round(time.time() - start, 1)}


figures = {"samples": samples, "size": [160, 120], "blender": bpy.app.version_string}
figures["principled"] = render("cycles.exr")
for m in bpy.data.materials:
    if m.use_nodes and "Principled BSDF" in m.node_tree.nodes:
        m.node_tree.nodes["Principled BSDF"].inputs["Specular"].default_value = 0.0
figures["no_specular"] = render("cycles-no-specular.exr")
# Lambertian, as igi reads a metallic-0 glTF material: Cycles' Diffuse BSDF
# at roughness 0 (Principled's diffuse is Burley's, brighter at grazing angles).
for m in bpy.data.materials:
    nodes = m.node_tree.nodes if m.use_nodes else {}
    if "Principled BSDF" not in nodes or nodes["Principled BSDF"].inputs["Metallic"].default_value > 0.0:
        continue
    principled = nodes["Principled BSDF"]
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Roughness"].default_value = 0.0
    colour = principled.inputs["Base Color"]
    if colour.links:
        m.node_tree.links.new(colour.links[0].from_socket, diffuse.inputs["Color"])
    else:
        diffuse.inputs["Color"].default_value = colour.default_value
    if principled.inputs["Emission Strength"].default_value > 0.0:
        emission = nodes.new("ShaderNodeEmission")
        emission.inputs["Color"].default_value = principled.inputs["Emission"].default_value
        emission.inputs["Strength"].default_value = principled.inputs["Emission Strength"].default_value
        add = nodes.new("ShaderNodeAddShader")
        m.node_tree.links.new(diffuse.outputs["BSDF"], add.inputs[0])
        m.node_tree.links.new(emission.outputs["Emission"], add.inputs[1])
        m.node_tree.links.new(add.outputs["Shader"], nodes["Material Output"].inputs["Surface"])
    else:
        m.node_tree.links.new(diffuse.outputs["BSDF"], nodes["Material Output"].inputs["Surface"])
figures["lambert"] = render("cycles-lambert.exr")
with open(os.path.join(out_dir, "cycles.json"), "w") as f:
    json.dump(figures, f, indent=2)
print(json.dumps(figures))
