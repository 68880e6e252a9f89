"""Maps a glTF 2.0 scene to a Mitsuba 3 scene dict (mi.load_dict) the way igi
reads it (README "Conventions"), for an independent reference render.

  metallic 0, KHR_materials_specular specularFactor 0 (igi's Lambert, as
                           --export-gltf writes it) -> twosided diffuse,
                           reflectance = baseColor x texture
  metallic 1, extras.igi_fresnel "constant" (--export-gltf's built-in metal) ->
                           twosided roughconductor, GGX, alpha = roughness^2,
                           perfect reflector tinted by baseColor (constant
                           Fresnel), or conductor (mirror) at roughness 0
  any other metallic-roughness material -> twosided gltf_metallic_roughness
                           (gltf_bsdf.py: the specification's BRDF, exactly as
                           igi reads it: fractional metallic, KHR_materials_specular,
                           KHR_materials_ior, metallicRoughnessTexture, each
                           texture with KHR_texture_transform)
  transmission          -> dielectric, int_ior = KHR_materials_ior (1.5), tint
  emission              -> area emitter, emissiveFactor x emissive_strength, front
                           (counter-clockwise) face only; emissive meshes drop
                           their vertex normals, since Mitsuba's area emitter
                           emits on the side of the shading normal
  KHR_lights_punctual   -> point (W/sr), directional (W/m^2), spot (W/sr, glTF's
                           smooth falloff as a texture over a sharp Mitsuba cone),
                           from glTF's candela and lux at 683 lm/W as igi reads
                           them (light_units "radiometric": as written)
  first perspective camera -> perspective, fov_axis y, box-filtered hdrfilm
  scene extras.environment [r, g, b] -> constant emitter of that radiance
                           (igi's constant sky; a map's file name is not mapped)

Opaque materials are two-sided because igi shades either side of a
double-sided face alike (common/material/bsdf.cpp); glass is not wrapped.
An emissiveTexture is read as its mean (igi's reading), an occlusionTexture
ignored (igi ignores it). Not mapped: normal maps (normalTexture), DDS
images (MSFT_texture_dds, AMD_split_roughnessMetallic), texture coordinate
sets other than TEXCOORD_0. Whatever the mapping cannot reproduce raises
UnsupportedFeature naming it.
"""
import math

import mitsuba as mi
import numpy as np

from gltf_reader import Gltf, GltfError, extension_names

mi.set_variant("scalar_rgb")
import gltf_bsdf  # noqa: E402,F401 (registers the gltf_metallic_roughness plugin, once a variant is set)

SUPPORTED_EXTENSIONS = {"KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior",
                        "KHR_materials_emissive_strength", "KHR_materials_specular", "KHR_texture_transform"}
IGNORABLE_ATTRIBUTES = ("TEXCOORD_", "TANGENT")  # unused without textures on them or normal maps
OTHER_TEXTURES = ("normalTexture",)
SPOT_PROFILE_TEXELS = 1024
MAX_SPOT_CONE = math.radians(85.0)  # Mitsuba's spot texture is projected over tan(cutoff)
NEAR_CLIP, FAR_CLIP = 1e-4, 1e8     # igi's camera rays are unclipped
LUMENS_PER_WATT = 683.0             # common/scene/light_units.h


class UnsupportedFeature(GltfError):
    pass


def unsupported(gltf, element, feature):
    raise UnsupportedFeature(f"{gltf.path}: {element}: {feature} is not supported by the Mitsuba mapping")


def check_file_features(gltf):
    doc = gltf.doc
    for name in sorted(extension_names(doc) - SUPPORTED_EXTENSIONS):
        unsupported(gltf, "extensions", f"extension {name}")
    for kind in ("skins", "animations"):
        if doc.get(kind):
            unsupported(gltf, kind, kind)
    morphed = any("weights" in m or any("targets" in p for p in m.get("primitives", [])) for m in doc.get("meshes", []))
    if morphed or any("weights" in n for n in doc.get("nodes", [])):
        unsupported(gltf, "meshes", "morph targets")


def rgb(value):
    return {"type": "rgb", "value": [float(c) for c in value]}


def decoded_image(gltf, index, srgb=True):
    """glTF image `index` as a linear float RGB array, decoded from sRGB as igi does (colour), or as stored (data)."""
    stream = mi.MemoryStream()
    stream.write(gltf.image_bytes(index))
    stream.seek(0)
    try:
        bitmap = mi.Bitmap(stream)
    except RuntimeError as error:
        gltf.fail(f"images[{index}]", f"cannot be decoded ({error})")
    bitmap.set_srgb_gamma(srgb)
    return np.array(bitmap.convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, srgb_gamma=False))


def check_sampler(gltf, texture, element):
    sampler = gltf.element("samplers", texture["sampler"]) if "sampler" in texture else {}
    if sampler.get("wrapS", 10497) != 10497 or sampler.get("wrapT", 10497) != 10497:
        unsupported(gltf, element, "a sampler wrap mode other than REPEAT")
    # Filters: igi reads every texture bilinearly without mipmaps (it warns), as the bitmaps here do.


def texture_info(gltf, info, element, name):
    """(glTF texture, Mitsuba to_uv transform or None) of a textureInfo."""
    transform = info.get("extensions", {}).get("KHR_texture_transform")
    if info.get("texCoord", 0) != 0 or (transform or {}).get("texCoord", 0) != 0:
        unsupported(gltf, element, f"a {name} on a texCoord other than 0")
    texture = gltf.element("textures", info.get("index"))
    check_sampler(gltf, texture, element)
    if "source" not in texture:
        unsupported(gltf, element, f"a {name} without a core image source (DDS, KTX)")
    if transform is None:
        return texture, None
    # u' = T R S u (KHR_texture_transform), R = [cos r, sin r; -sin r, cos r]
    (ox, oy), r, (sx, sy) = transform.get("offset", [0, 0]), transform.get("rotation", 0.0), transform.get("scale", [1, 1])
    c, s = math.cos(r), math.sin(r)
    matrix = [[c * sx, s * sy, ox], [-s * sx, c * sy, oy], [0.0, 0.0, 1.0]]
    return texture, mi.ScalarTransform3f(mi.ScalarMatrix3f(matrix))


def bitmap_texture(values, to_uv):
    texture = {"type": "bitmap", "bitmap": mi.Bitmap(values.astype(np.float32)), "raw": True,
               "filter_type": "bilinear", "wrap_mode": "repeat"}
    if to_uv is not None:
        texture["to_uv"] = to_uv
    return texture


def base_colour(gltf, pbr, element):
    """baseColorFactor (rgb) times the base-colour texture: a Mitsuba texture dict."""
    factor = pbr.get("baseColorFactor", [1, 1, 1, 1])[:3]
    info = pbr.get("baseColorTexture")
    if info is None:
        return rgb(factor)
    texture, to_uv = texture_info(gltf, info, element, "baseColorTexture")
    return bitmap_texture(decoded_image(gltf, texture.get("source")) * np.asarray(factor, dtype=np.float32), to_uv)


def metallic_roughness(gltf, pbr, element):
    """(metallic, roughness) textures: the factors times the metallicRoughnessTexture's blue and green, linear."""
    metallic, roughness = pbr.get("metallicFactor", 1.0), pbr.get("roughnessFactor", 1.0)
    info = pbr.get("metallicRoughnessTexture")
    if info is None:
        return {"type": "uniform", "value": float(metallic)}, {"type": "uniform", "value": float(roughness)}
    texture, to_uv = texture_info(gltf, info, element, "metallicRoughnessTexture")
    texels = decoded_image(gltf, texture.get("source"), srgb=False)
    return (bitmap_texture(texels[:, :, 2:3] * np.float32(metallic), to_uv),
            bitmap_texture(texels[:, :, 1:2] * np.float32(roughness), to_uv))


def coat(material):
    """(F0, weight) of the dielectric coat: KHR_materials_ior and KHR_materials_specular."""
    extensions = material.get("extensions", {})
    ior = extensions.get("KHR_materials_ior", {}).get("ior", 1.5)
    specular = extensions.get("KHR_materials_specular", {})
    colour = np.asarray(specular.get("specularColorFactor", [1, 1, 1]), dtype=np.float64)
    f0 = np.minimum(((ior - 1.0) / (ior + 1.0)) ** 2 * np.maximum(colour, 0.0), 1.0)
    return f0.tolist(), float(min(max(specular.get("specularFactor", 1.0), 0.0), 1.0))


def glass_ior(gltf, material, element):
    """KHR_materials_ior for a transmissive material, None for an opaque one."""
    transmission = material.get("extensions", {}).get("KHR_materials_transmission")
    factor = transmission.get("transmissionFactor", 0.0) if transmission else 0.0
    if factor == 0.0:
        return None
    if factor != 1.0 or "transmissionTexture" in transmission:
        unsupported(gltf, element, "partial transmission (transmissionFactor below 1 or a transmissionTexture)")
    return material["extensions"].get("KHR_materials_ior", {}).get("ior", 1.5)


def bsdf_dict(gltf, material, element):
    pbr = material.get("pbrMetallicRoughness", {})
    colour = base_colour(gltf, pbr, element)
    ior = glass_ior(gltf, material, element)
    if ior is not None:
        return {"type": "dielectric", "int_ior": float(ior), "ext_ior": 1.0, "specular_transmittance": colour}
    metallic, roughness = pbr.get("metallicFactor", 1.0), pbr.get("roughnessFactor", 1.0)
    f0, weight = coat(material)
    constant_fresnel = material.get("extras", {}).get("igi_fresnel") == "constant"
    textured = "metallicRoughnessTexture" in pbr
    if metallic == 0.0 and weight == 0.0 and not textured:
        inner = {"type": "diffuse", "reflectance": colour}
    elif metallic == 1.0 and constant_fresnel and roughness > 0.0 and not textured:
        inner = {"type": "roughconductor", "distribution": "ggx", "alpha": float(roughness) ** 2,
                 "material": "none", "specular_reflectance": colour, "sample_visible": True}
    elif metallic == 1.0 and constant_fresnel and not textured:
        inner = {"type": "conductor", "material": "none", "specular_reflectance": colour}
    else:
        metallic_texture, roughness_texture = metallic_roughness(gltf, pbr, element)
        inner = {"type": "gltf_metallic_roughness", "base_color": colour, "metallic": metallic_texture,
                 "roughness": roughness_texture, "f0": f0, "weight": weight}
    return {"type": "twosided", "bsdf": inner}


def check_material_features(gltf, material, element):
    if not material.get("doubleSided", False):
        unsupported(gltf, element, "a single-sided material (doubleSided false: igi culls its back for camera rays only)")
    specular = material.get("extensions", {}).get("KHR_materials_specular", {})
    if "specularTexture" in specular or "specularColorTexture" in specular:
        unsupported(gltf, element, "KHR_materials_specular's textures (igi reads its factors)")
    for name in OTHER_TEXTURES:
        if name in material:
            unsupported(gltf, element, name)
    mode = material.get("alphaMode", "OPAQUE")
    if mode != "OPAQUE" and "baseColorTexture" in material.get("pbrMetallicRoughness", {}):
        unsupported(gltf, element, f"alphaMode {mode} with a baseColorTexture")


def is_cut_out(material):
    """alphaMode MASK (BLEND: cutoff 0.5, as igi) with baseColorFactor alpha under the cutoff."""
    mode = material.get("alphaMode", "OPAQUE")
    if mode == "OPAQUE":
        return False
    cutoff = material.get("alphaCutoff", 0.5) if mode == "MASK" else 0.5
    return material.get("pbrMetallicRoughness", {}).get("baseColorFactor", [1, 1, 1, 1])[3] < cutoff


def emission(gltf, material, element):
    """Radiance: emissiveFactor x strength x the emissiveTexture's mean (igi's reading of it)."""
    strength = material.get("extensions", {}).get("KHR_materials_emissive_strength", {}).get("emissiveStrength", 1.0)
    radiance = np.asarray(material.get("emissiveFactor", [0, 0, 0]), dtype=np.float64) * strength
    if "emissiveTexture" in material and np.any(radiance > 0):
        texture, _ = texture_info(gltf, material["emissiveTexture"], element, "emissiveTexture")
        radiance = radiance * decoded_image(gltf, texture.get("source")).reshape(-1, 3).mean(axis=0)
    return radiance.tolist() if np.any(radiance > 0) else None


class MappedMaterial:
    """A glTF material as Mitsuba objects: the shared BSDF, its emission, its visibility."""

    def __init__(self, gltf, index):
        element = f"materials[{index}]"
        material = gltf.element("materials", index)
        check_material_features(gltf, material, element)
        self.bsdf = mi.load_dict(bsdf_dict(gltf, material, element))
        self.radiance = emission(gltf, material, element)
        self.cut_out = is_cut_out(material)
        pbr = material.get("pbrMetallicRoughness", {})
        self.textured = "baseColorTexture" in pbr or "metallicRoughnessTexture" in pbr


def check_attributes(gltf, attributes, element):
    for name in attributes:
        if name not in ("POSITION", "NORMAL") and not name.startswith(IGNORABLE_ATTRIBUTES):
            unsupported(gltf, element, f"vertex attribute {name}")
    if "POSITION" not in attributes:
        gltf.fail(element, "no POSITION")


def triangle_indices(gltf, primitive, vertex_count, element):
    if "indices" in primitive:
        indices = gltf.accessor(primitive["indices"]).reshape(-1).astype(np.int64)
    else:
        indices = np.arange(vertex_count)
    if len(indices) % 3 != 0 or (len(indices) and not 0 <= indices.min() <= indices.max() < vertex_count):
        gltf.fail(element, "indices are not whole triangles within POSITION")
    return indices.reshape(-1, 3)


def world_normals(gltf, normals, linear, element):
    """Normals through the inverse transpose of the node's linear part, unit length."""
    out = normals @ np.linalg.inv(linear)
    length = np.linalg.norm(out, axis=1, keepdims=True)
    if not np.all(np.isfinite(length)) or np.any(length < 1e-12):
        gltf.fail(element, "zero or non-finite vertex normals")
    return out / length


def make_mesh(name, positions, faces, normals, uvs, props):
    mesh = mi.Mesh(name, len(positions), len(faces), props, has_vertex_normals=normals is not None,
                   has_vertex_texcoords=uvs is not None)
    params = mi.traverse(mesh)
    params["vertex_positions"] = positions.astype(np.float32).reshape(-1)
    params["faces"] = faces.astype(np.uint32).reshape(-1)
    if normals is not None:
        params["vertex_normals"] = normals.astype(np.float32).reshape(-1)
    if uvs is not None:
        params["vertex_texcoords"] = uvs.astype(np.float32).reshape(-1)
    params.update()
    return mesh


def primitive_mesh(gltf, primitive, world, material, element):
    """One triangle primitive in world space as a Mitsuba mesh; None if it has no triangles."""
    if primitive.get("mode", 4) != 4:
        unsupported(gltf, element, f"primitive mode {primitive['mode']} (only TRIANGLES)")
    attributes = primitive.get("attributes", {})
    check_attributes(gltf, attributes, element)
    positions = gltf.float_accessor(attributes["POSITION"])
    faces = triangle_indices(gltf, primitive, len(positions), element)
    if len(faces) == 0:
        return None
    linear = world[:3, :3]
    if np.linalg.det(linear) < 0:  # a mirroring transform turns the winding over (glTF spec)
        faces = faces[:, [0, 2, 1]]
    normals = None
    if "NORMAL" in attributes and material.radiance is None:
        normals = world_normals(gltf, gltf.float_accessor(attributes["NORMAL"]), linear, element)
    uvs = None
    if material.textured:
        if "TEXCOORD_0" not in attributes:
            unsupported(gltf, element, "a baseColorTexture without TEXCOORD_0")
        uvs = gltf.float_accessor(attributes["TEXCOORD_0"])
    props = mi.Properties()
    props["bsdf"] = material.bsdf
    if material.radiance is not None:
        props["emitter"] = mi.load_dict({"type": "area", "radiance": rgb(material.radiance)})
    return make_mesh(element, positions @ linear.T + world[:3, 3], faces, normals, uvs, props)


def node_meshes(gltf, node_index, node, world, materials):
    """{key: mi.Mesh} of the node's mesh's primitives."""
    out = {}
    for p, primitive in enumerate(gltf.element("meshes", node["mesh"]).get("primitives", [])):
        element = f"nodes[{node_index}].meshes[{node['mesh']}].primitives[{p}]"
        if "material" not in primitive:
            unsupported(gltf, element, "a primitive without a material (glTF's default material is single-sided)")
        gltf.element("materials", primitive["material"])  # fails on an index out of range
        material = materials[primitive["material"]]
        mesh = None if material.cut_out else primitive_mesh(gltf, primitive, world, material, element)
        if mesh is not None:
            out[f"mesh_{node_index}_{p}"] = mesh
    return out


def look_at(origin, forward, up):
    return mi.ScalarTransform4f().look_at(origin=origin.tolist(), target=(origin + forward).tolist(), up=up.tolist())


def spot_profile(inner, outer):
    """glTF's smooth spot falloff (as igi's spot_attenuation) over Mitsuba's spot
    texture, whose uv runs over [-tan(cutoff), tan(cutoff)] across the cone."""
    centres = (np.arange(SPOT_PROFILE_TEXELS) + 0.5) / SPOT_PROFILE_TEXELS * 2.0 - 1.0
    tan_theta = np.hypot(centres[None, :], centres[:, None]) * math.tan(outer)
    cos_theta = 1.0 / np.sqrt(1.0 + tan_theta ** 2)
    scale = 1.0 / max(0.001, math.cos(inner) - math.cos(outer))
    falloff = np.clip((cos_theta - math.cos(outer)) * scale, 0.0, 1.0) ** 2
    return {"type": "bitmap", "bitmap": mi.Bitmap(np.repeat(falloff[:, :, None], 3, axis=2).astype(np.float32)),
            "raw": True, "filter_type": "bilinear", "wrap_mode": "clamp"}


def spot_light(gltf, light, position, direction, intensity, element):
    spot = light.get("spot", {})
    inner, outer = spot.get("innerConeAngle", 0.0), spot.get("outerConeAngle", math.pi / 4)
    if not 0.0 <= inner < outer <= MAX_SPOT_CONE:
        unsupported(gltf, element, f"spot cone angles inner {inner}, outer {outer} (needs 0 <= inner < outer <= 85 degrees)")
    up = np.array([0.0, 1.0, 0.0]) if abs(direction[1]) < 0.9 else np.array([1.0, 0.0, 0.0])
    return {"type": "spot", "to_world": look_at(position, direction, up), "intensity": rgb(intensity),
            "cutoff_angle": math.degrees(outer), "beam_width": math.degrees(outer),
            "texture": spot_profile(inner, outer)}


def punctual_light(gltf, node_index, node, world, light_units):
    """The node's KHR_lights_punctual light as a Mitsuba emitter dict."""
    index = node["extensions"]["KHR_lights_punctual"].get("light")
    lights = gltf.doc.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
    element = f"nodes[{node_index}]: KHR_lights_punctual light {index}"
    if not isinstance(index, int) or not 0 <= index < len(lights):
        gltf.fail(element, f"does not exist (the file has {len(lights)} lights)")
    light = lights[index]
    if "range" in light:
        unsupported(gltf, element, "light range")
    intensity = np.asarray(light.get("color", [1, 1, 1]), dtype=np.float64) * light.get("intensity", 1.0)
    if light_units == "photometric":
        intensity /= LUMENS_PER_WATT
    position = world[:3, 3]
    direction = world[:3, :3] @ np.array([0.0, 0.0, -1.0])
    direction /= np.linalg.norm(direction)
    kind = light.get("type")
    if kind == "point":
        return {"type": "point", "position": position.tolist(), "intensity": rgb(intensity)}
    if kind == "directional":
        return {"type": "directional", "direction": direction.tolist(), "irradiance": rgb(intensity)}
    if kind == "spot":
        return spot_light(gltf, light, position, direction, intensity, element)
    unsupported(gltf, element, f"light type '{kind}'")


def first_camera(gltf, nodes):
    """(perspective camera dict, world matrix) of the first node with a perspective camera."""
    for _, node, world in nodes:
        if "camera" in node:
            camera = gltf.element("cameras", node["camera"])
            if camera.get("type") == "perspective":
                return camera["perspective"], world
    unsupported(gltf, "cameras", "a scene without a perspective camera (igi would frame the bounding box)")


def sensor_dict(gltf, nodes, width, height):
    """glTF cameras look down -Z with +Y up; pixel (0, 0) is the top-left, as in igi."""
    perspective, world = first_camera(gltf, nodes)
    forward = world[:3, :3] @ np.array([0.0, 0.0, -1.0])
    forward /= np.linalg.norm(forward)
    up = world[:3, :3] @ np.array([0.0, 1.0, 0.0])
    up -= np.dot(up, forward) * forward
    return {"type": "perspective", "fov_axis": "y", "fov": math.degrees(perspective["yfov"]),
            "near_clip": NEAR_CLIP, "far_clip": FAR_CLIP,
            "to_world": look_at(world[:3, 3], forward, up / np.linalg.norm(up)),
            "sampler": {"type": "independent"},
            "film": {"type": "hdrfilm", "width": width, "height": height, "pixel_format": "rgb",
                     "rfilter": {"type": "box"}}}


def environment(gltf):
    """The default scene's sky, extras.environment, as igi reads it (common/scene/gltf_loader.cpp):
    a constant radiance [r, g, b] becomes a constant emitter; None without one."""
    scenes = gltf.doc.get("scenes", [])
    index = gltf.doc.get("scene", 0)
    extras = scenes[index].get("extras", {}) if index < len(scenes) else {}
    value = extras.get("environment") if isinstance(extras, dict) else None
    if value is None:
        return None
    if isinstance(value, list) and len(value) == 3 and all(isinstance(c, (int, float)) for c in value):
        return {"type": "constant", "radiance": rgb(value)}
    unsupported(gltf, "scenes", "extras.environment other than a constant [r, g, b] (a map)")


def scene_dict(path, width, height, light_units="photometric"):
    """The Mitsuba scene dict of the glTF file at `path`, for a width x height
    image; its lamps read in `light_units` (igi's --light-units)."""
    if light_units not in ("photometric", "radiometric"):
        raise ValueError(f"light_units: expected photometric or radiometric, got '{light_units}'")
    gltf = Gltf(path)
    check_file_features(gltf)
    nodes = gltf.world_nodes()
    materials = [MappedMaterial(gltf, i) for i in range(len(gltf.doc.get("materials", [])))]
    out = {"type": "scene", "sensor": sensor_dict(gltf, nodes, width, height),
           "integrator": {"type": "path", "max_depth": -1, "rr_depth": 5, "hide_emitters": False}}
    for node_index, node, world in nodes:
        if "mesh" in node:
            out.update(node_meshes(gltf, node_index, node, world, materials))
        if "KHR_lights_punctual" in node.get("extensions", {}):
            out[f"light_{node_index}"] = punctual_light(gltf, node_index, node, world, light_units)
    sky = environment(gltf)
    if sky:
        out["environment"] = sky
    return out
