"""Unit tests of the glTF -> Mitsuba mapping on tiny hand-made scenes.

  cd scripts/mitsuba && python -m unittest test_mapping

Each scene is written here, as a .gltf with data: URIs, a .gltf with an
external .bin, or a .glb; renders are 32 x 32 pixels at a few samples.
"""
import base64
import json
import math
import os
import struct
import tempfile
import unittest

import mitsuba as mi
import numpy as np

from gltf_reader import GltfError
from gltf_to_mitsuba import UnsupportedFeature, bsdf_dict, scene_dict

SIZE = 32


class SceneFile:
    """A glTF document under construction, with one binary buffer."""

    def __init__(self):
        self.blob = bytearray()
        self.doc = {"asset": {"version": "2.0"}, "buffers": [{}], "bufferViews": [], "accessors": [],
                    "meshes": [], "materials": [], "nodes": [], "scenes": [{"nodes": []}], "scene": 0}

    def accessor(self, values, kind, component=5126):
        values = np.asarray(values, dtype=np.float32 if component == 5126 else np.uint32)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.blob), "byteLength": values.nbytes})
        self.blob += values.tobytes()
        self.doc["accessors"].append({"bufferView": len(self.doc["bufferViews"]) - 1, "componentType": component,
                                      "count": len(values), "type": kind})
        return len(self.doc["accessors"]) - 1

    def material(self, colour=(0.5, 0.5, 0.5), metallic=0.0, roughness=1.0, emission=None, lambert=True, **extra):
        """lambert: metallic 0 with no specular reflection (igi's Lambert, as --export-gltf writes it)."""
        material = {"doubleSided": True, "pbrMetallicRoughness": {
            "baseColorFactor": list(colour) + [1.0], "metallicFactor": metallic, "roughnessFactor": roughness}}
        if lambert and metallic == 0.0:
            material["extensions"] = {"KHR_materials_specular": {"specularFactor": 0.0}}
        if emission is not None:
            material["emissiveFactor"] = [1.0, 1.0, 1.0]
            material.setdefault("extensions", {})["KHR_materials_emissive_strength"] = {"emissiveStrength": emission}
        material.update(extra)
        self.doc["materials"].append(material)
        return len(self.doc["materials"]) - 1

    def node(self, root=True, **node):
        self.doc["nodes"].append(node)
        if root:
            self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)
        return len(self.doc["nodes"]) - 1

    def mesh(self, positions, material, normals=None, indices=None, uvs=None, **node):
        """A one-primitive mesh on a new root node."""
        attributes = {"POSITION": self.accessor(positions, "VEC3")}
        if normals is not None:
            attributes["NORMAL"] = self.accessor(normals, "VEC3")
        if uvs is not None:
            attributes["TEXCOORD_0"] = self.accessor(uvs, "VEC2")
        primitive = {"attributes": attributes, "material": material}
        if indices is not None:
            primitive["indices"] = self.accessor(indices, "SCALAR", 5125)
        self.doc["meshes"].append({"primitives": [primitive]})
        return self.node(mesh=len(self.doc["meshes"]) - 1, **node)

    def quad(self, centre, half, material, facing=+1, normals=None, **node):
        """A square in the plane z = centre.z, counter-clockwise seen from +z (facing +1) or -z."""
        x, y, z = centre
        corners = [(x - half, y - half, z), (x + half, y - half, z), (x + half, y + half, z), (x - half, y + half, z)]
        order = [0, 1, 2, 0, 2, 3] if facing > 0 else [0, 2, 1, 0, 3, 2]
        return self.mesh(corners, material, normals=normals, indices=order, **node)

    def camera(self, yfov=0.5, **node):
        self.doc.setdefault("cameras", []).append({"type": "perspective", "perspective": {"yfov": yfov, "znear": 0.01}})
        return self.node(camera=len(self.doc["cameras"]) - 1, **node)

    def light(self, light, **node):
        lights = self.doc.setdefault("extensions", {}).setdefault("KHR_lights_punctual", {}).setdefault("lights", [])
        lights.append(light)
        self.doc.setdefault("extensionsUsed", []).append("KHR_lights_punctual")
        return self.node(extensions={"KHR_lights_punctual": {"light": len(lights) - 1}}, **node)

    def write(self, path, external_bin=False):
        doc = json.loads(json.dumps(self.doc))
        doc["buffers"][0]["byteLength"] = len(self.blob)
        if path.endswith(".glb"):
            body, blob = json.dumps(doc).encode().ljust(4 * -(-len(json.dumps(doc)) // 4)), bytes(self.blob)
            chunks = struct.pack("<II", len(body), 0x4E4F534A) + body + struct.pack("<II", len(blob), 0x004E4942) + blob
            data = struct.pack("<III", 0x46546C67, 2, 12 + len(chunks)) + chunks
        elif external_bin:
            doc["buffers"][0]["uri"] = os.path.basename(path) + ".bin"
            with open(path + ".bin", "wb") as f:
                f.write(self.blob)
            data = json.dumps(doc).encode()
        else:
            doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(self.blob).decode()
            data = json.dumps(doc).encode()
        with open(path, "wb") as f:
            f.write(data)
        return path


def lit_quad_scene(emitter_facing=-1, emitter_normals=None, quad_facing=+1):
    """Camera at the origin looking down -z at a diffuse quad (albedo 0.5) at z = -1;
    a large black emitter of radiance 1 at z = +1, facing the quad when emitter_facing = -1."""
    scene = SceneFile()
    scene.camera(yfov=0.3)
    scene.quad((0, 0, -1), 1.0, scene.material(), facing=quad_facing)
    scene.quad((0, 0, 1), 100.0, scene.material(colour=(0, 0, 0), emission=1.0), facing=emitter_facing,
               normals=emitter_normals)
    return scene


class MappingTest(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.folder.cleanup()

    def path(self, name):
        return os.path.join(self.folder.name, name)

    def render(self, scene, name="scene.gltf", spp=16, **write):
        path = scene.write(self.path(name), **write)
        return np.array(mi.render(mi.load_dict(scene_dict(path, SIZE, SIZE)), spp=spp))

    def test_front_facing_emitter_lights_the_quad(self):
        # Radiance = albedo x L x the emitter's form factor, ~1 for a 200 m square 2 m away.
        image = self.render(lit_quad_scene())
        self.assertAlmostEqual(float(image.mean()), 0.5, delta=0.02)

    def test_back_facing_emitter_gives_black(self):
        self.assertEqual(float(self.render(lit_quad_scene(emitter_facing=+1)).max()), 0.0)

    def test_diffuse_reflects_on_its_back_as_igi(self):
        image = self.render(lit_quad_scene(quad_facing=-1))
        self.assertAlmostEqual(float(image.mean()), 0.5, delta=0.02)

    def test_emission_follows_the_winding_not_the_normals(self):
        against_winding = [(0, 0, 1)] * 4  # the front (winding) faces -z
        image = self.render(lit_quad_scene(emitter_normals=against_winding))
        self.assertAlmostEqual(float(image.mean()), 0.5, delta=0.02)

    def test_glb_and_external_bin_load_alike(self):
        for name, write in (("scene.glb", {}), ("scene.gltf", {"external_bin": True})):
            with self.subTest(name):
                image = self.render(lit_quad_scene(), name=name, **write)
                self.assertAlmostEqual(float(image.mean()), 0.5, delta=0.02)

    def test_buffer_outside_the_folder_is_an_error(self):
        scene = lit_quad_scene()
        path = scene.write(self.path("scene.gltf"))
        with open(path) as f:
            doc = json.load(f)
        doc["buffers"][0]["uri"] = "../elsewhere.bin"
        with open(path, "w") as f:
            json.dump(doc, f)
        with self.assertRaisesRegex(GltfError, "outside the scene's folder"):
            scene_dict(path, SIZE, SIZE)

    def test_camera_sees_left_as_left_and_up_as_up(self):
        # An emitter facing the camera in the top-left quadrant of the view; the
        # camera is turned (rotation about y) to look down -x from x = +5.
        scene = SceneFile()
        half_turn = math.sqrt(0.5)
        scene.camera(yfov=1.0, translation=[5, 0, 0], rotation=[0, half_turn, 0, half_turn])
        light = scene.material(colour=(0, 0, 0), emission=1.0)
        # Seen from +x looking down -x, left is +z and up is +y; the quad faces +x.
        corners = [(0, 0.2, 0.2), (0, 0.2, 1.0), (0, 1.0, 1.0), (0, 1.0, 0.2)]
        scene.mesh(corners, light, indices=[0, 2, 1, 0, 3, 2])
        image = self.render(scene).mean(axis=2)
        half = SIZE // 2
        self.assertGreater(image[:half, :half].mean(), 0.05)  # the quad covers ~9% of it
        self.assertEqual(image[half:, :].max(), 0.0)
        self.assertEqual(image[:, half:].max(), 0.0)

    def test_trs_and_hierarchy_transform_positions_and_normals(self):
        scene = SceneFile()
        scene.camera()
        diagonal = (math.sqrt(0.5), math.sqrt(0.5), 0)
        child = scene.mesh([(1, 0, 0), (0, 1, 0), (0, 0, 1)], scene.material(), normals=[diagonal] * 3,
                           root=False, translation=[0, 0, 5], scale=[2, 1, 1])
        quarter = math.sqrt(0.5)
        scene.node(children=[child], translation=[10, 0, 0], rotation=[0, 0, quarter, quarter])  # 90 deg about z
        path = scene.write(self.path("scene.gltf"))
        mesh = next(v for k, v in scene_dict(path, SIZE, SIZE).items() if k.startswith("mesh"))
        params = mi.traverse(mesh)
        positions = np.array(params["vertex_positions"]).reshape(-1, 3)
        # Child: scale x by 2, move z by 5; parent: (x, y) -> (-y, x), move x by 10.
        np.testing.assert_allclose(positions, [(10, 2, 5), (9, 0, 5), (10, 0, 6)], atol=1e-6)
        # Normals by the inverse transpose: (1, 1, 0) -> (1/2, 1, 0) -> (-1, 1/2, 0), made unit.
        normals = np.array(params["vertex_normals"]).reshape(-1, 3)
        np.testing.assert_allclose(normals, [np.array([-2, 1, 0]) / math.sqrt(5)] * 3, atol=1e-6)

    def test_mirroring_transform_keeps_the_front_face(self):
        # Mirrored in z, the emitter moves to z = +1 and its front (+z in its own
        # space) mirrors to -z, towards the quad, once the winding is turned over
        # as glTF asks: it lights the quad.
        scene = SceneFile()
        scene.camera(yfov=0.3)
        scene.quad((0, 0, -1), 1.0, scene.material())
        scene.quad((0, 0, -1), 100.0, scene.material(colour=(0, 0, 0), emission=1.0), facing=+1,
                   scale=[1, 1, -1])
        self.assertAlmostEqual(float(self.render(scene).mean()), 0.5, delta=0.02)

    def test_material_models(self):
        constant = {"extras": {"igi_fresnel": "constant"}}
        cases = [
            (dict(metallic=0.0), "diffuse", {}),
            (dict(metallic=1.0, roughness=0.5, **constant), "roughconductor", {"alpha": 0.25, "distribution": "ggx"}),
            (dict(metallic=1.0, roughness=0.0, **constant), "conductor", {"material": "none"}),
            (dict(metallic=0.0, lambert=False), "gltf_metallic_roughness", {"f0": [(0.5 / 2.5) ** 2] * 3, "weight": 1.0}),
            (dict(metallic=0.3, roughness=0.5), "gltf_metallic_roughness", {"metallic": {"type": "uniform", "value": 0.3}}),
            (dict(metallic=1.0, roughness=0.5), "gltf_metallic_roughness", {"roughness": {"type": "uniform", "value": 0.5}}),
        ]
        for options, kind, fields in cases:
            with self.subTest(kind):
                scene = SceneFile()
                bsdf = bsdf_dict(None, scene.doc["materials"][scene.material(**options)], "material")
                self.assertEqual(bsdf["type"], "twosided")
                self.assertEqual(bsdf["bsdf"]["type"], kind)
                for key, value in fields.items():
                    self.assertEqual(bsdf["bsdf"][key], value)
        glass = {"pbrMetallicRoughness": {"metallicFactor": 0.0}, "extensions": {
            "KHR_materials_transmission": {"transmissionFactor": 1.0}, "KHR_materials_ior": {"ior": 1.7}}}
        self.assertEqual(bsdf_dict(None, glass, "material")["type"], "dielectric")
        self.assertEqual(bsdf_dict(None, glass, "material")["int_ior"], 1.7)

    def test_metallic_roughness_samples_its_own_density(self):
        # The mean of sample weights (f cos / pdf) equals f cos integrated over the
        # hemisphere by a midpoint rule: sampling, pdf and eval of gltf_bsdf.py agree.
        scene = SceneFile()
        material = scene.doc["materials"][scene.material(colour=(0.8, 0.5, 0.2), metallic=0.3, roughness=0.6)]
        bsdf = mi.load_dict(bsdf_dict(None, material, "material")["bsdf"])
        si = mi.SurfaceInteraction3f()
        si.wi = mi.Vector3f(0.6, 0.0, 0.8)
        ctx = mi.BSDFContext()
        rng = np.random.default_rng(3)
        sampled = np.zeros(3)
        for _ in range(20000):
            _, weight = bsdf.sample(ctx, si, float(rng.random()), mi.Point2f(*rng.random(2)))
            sampled += np.array(weight)
        sampled /= 20000
        integral, n = np.zeros(3), 160
        for i in range(n):
            cos_theta = (i + 0.5) / n
            for j in range(2 * n):
                phi = (j + 0.5) / (2 * n) * 2 * math.pi
                sin_theta = math.sqrt(1 - cos_theta * cos_theta)
                wo = mi.Vector3f(sin_theta * math.cos(phi), sin_theta * math.sin(phi), cos_theta)
                integral += np.array(bsdf.eval(ctx, si, wo)) * (1.0 / n) * (math.pi / n)
        np.testing.assert_allclose(sampled, integral, rtol=0.02)

    def test_texture_is_decoded_from_srgb_with_v_down(self):
        # A 1 x 2 texture: sRGB 188 in the top row (v = 0 in glTF), black below.
        mi.Bitmap(np.array([[[188] * 3], [[0] * 3]], dtype=np.uint8)).write(self.path("texture.png"))
        scene = SceneFile()
        scene.camera()
        material = scene.material(colour=(0.8, 0.8, 0.8))
        scene.doc["materials"][material]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
        scene.doc.update(images=[{"uri": "texture.png"}], textures=[{"source": 0}])
        corners = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
        scene.mesh(corners, material, indices=[0, 1, 2, 0, 2, 3], uvs=[(0, 1), (1, 1), (1, 0), (0, 0)])
        path = scene.write(self.path("scene.gltf"))
        mesh = next(v for k, v in scene_dict(path, SIZE, SIZE).items() if k.startswith("mesh"))
        si = mi.SurfaceInteraction3f()
        si.wi = mi.Vector3f(0, 0, 1)
        linear = ((188 / 255 + 0.055) / 1.055) ** 2.4
        for v, expected in ((0.25, 0.8 * linear), (0.75, 0.0)):  # the rows' centres
            si.uv = mi.Point2f(0.5, v)
            with self.subTest(v=v):
                self.assertAlmostEqual(float(mesh.bsdf().eval_diffuse_reflectance(si)[0]), expected, delta=1e-4)

    def test_point_and_directional_lights_are_photometric(self):
        # Diffuse albedo 0.5 facing +z: radiance = 0.5 / pi x irradiance; glTF's
        # candela and lux are W/sr and W/m^2 times 683.
        for light, node, irradiance in (
                ({"type": "point", "intensity": 8.0 * 683}, {"translation": [0, 0, 1]}, 8.0),
                ({"type": "directional", "intensity": 3.0 * 683}, {}, 3.0)):  # node -z: straight down onto the quad
            with self.subTest(light["type"]):
                scene = SceneFile()
                scene.camera(yfov=0.01, translation=[0, 0, 0.5])
                scene.quad((0, 0, -1), 1.0, scene.material())
                scene.light(light, **node)
                expected = 0.5 / math.pi * irradiance / (4.0 if light["type"] == "point" else 1.0)
                self.assertAlmostEqual(float(self.render(scene, spp=4).mean()), expected, delta=0.01 * expected)

    def test_spot_falloff_is_gltfs(self):
        scene = SceneFile()
        scene.camera()
        inner, outer = math.radians(14), math.radians(20)
        scene.light({"type": "spot", "intensity": 40.0 * 683, "spot": {"innerConeAngle": inner, "outerConeAngle": outer}})
        path = scene.write(self.path("scene.gltf"))
        emitter = mi.load_dict(next(v for k, v in scene_dict(path, SIZE, SIZE).items() if k.startswith("light")))
        for degrees in (0, 10, 15, 17, 19, 19.9, 21):
            theta = math.radians(degrees)
            it = mi.Interaction3f()
            it.p = mi.ScalarPoint3f(math.sin(theta), 0.0, -math.cos(theta))  # 1 m away, theta off -z
            _, value = emitter.sample_direction(it, mi.Point2f(0.5, 0.5))
            a = min(max((math.cos(theta) - math.cos(outer)) / (math.cos(inner) - math.cos(outer)), 0.0), 1.0)
            with self.subTest(degrees=degrees):
                self.assertAlmostEqual(float(value[0]), 40.0 * a * a, delta=0.002 * 40.0)

    def test_constant_sky_is_seen_and_lights_the_scene(self):
        # No light but the scene's extras.environment: a pixel that sees the
        # sky has its radiance, and a white floor under it reflects about as
        # much (an open plane under a uniform sky: E = pi L, L_out = albedo L).
        scene = SceneFile()
        scene.camera(yfov=0.3)
        scene.quad((0, 0, -1), 0.05, scene.material(colour=(1, 1, 1)))  # a third of the view, in the middle
        scene.doc["scenes"][0]["extras"] = {"environment": [0.5, 1.0, 2.0]}
        image = self.render(scene, spp=256)
        np.testing.assert_allclose(image[0, 0], [0.5, 1.0, 2.0], rtol=1e-4)  # a corner sees the sky
        middle = image[SIZE // 2 - 4:SIZE // 2 + 4, SIZE // 2 - 4:SIZE // 2 + 4].reshape(-1, 3).mean(axis=0)
        np.testing.assert_allclose(middle, [0.5, 1.0, 2.0], rtol=0.03)  # the quad, lit by the sky above it
        scene.doc["scenes"][0]["extras"] = {"environment": "sky.hdr"}
        with self.assertRaisesRegex(UnsupportedFeature, "extras.environment"):
            scene_dict(scene.write(self.path("map.gltf")), SIZE, SIZE)

    def test_unsupported_features_are_named(self):
        def normal_map(doc):
            doc["materials"][0]["normalTexture"] = {"index": 0}

        def single_sided(doc):
            doc["materials"][0]["doubleSided"] = False

        def extension(doc):
            doc["extensionsUsed"] = ["MSFT_texture_dds"]

        def lines(doc):
            doc["meshes"][0]["primitives"][0]["mode"] = 1

        def no_camera(doc):
            doc["nodes"][0].pop("camera")

        def area_light_kind(doc):
            doc["extensions"] = {"KHR_lights_punctual": {"lights": [{"type": "area"}]}}
            doc["nodes"].append({"extensions": {"KHR_lights_punctual": {"light": 0}}})
            doc["scenes"][0]["nodes"].append(len(doc["nodes"]) - 1)

        cases = [(normal_map, "normalTexture"), (single_sided, "single-sided"),
                 (extension, "MSFT_texture_dds"), (lines, "primitive mode 1"),
                 (no_camera, "without a perspective camera"), (area_light_kind, "light type 'area'")]
        for change, message in cases:
            with self.subTest(message):
                scene = lit_quad_scene()
                change(scene.doc)
                with self.assertRaisesRegex(UnsupportedFeature, message):
                    scene_dict(scene.write(self.path("scene.gltf")), SIZE, SIZE)


if __name__ == "__main__":
    unittest.main()
