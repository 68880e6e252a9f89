"""glTF 2.0's metallic-roughness BRDF (the specification's Appendix B, with
KHR_materials_specular) as a Mitsuba 3 BSDF plugin, "gltf_metallic_roughness":
Mitsuba has no plugin of this model (its principled BSDF has Burley's diffuse,
a separable Smith term and another Fresnel blend), so the reference renders it
with this one, written from the specification, sharing no code with igi's
common/material/.

  f = (1 - metallic) [(1 - w max(F_d)) base / pi + w F_d D V] + metallic F_m D V
  F_d = f0 + (1 - f0) (1 - |v.h|)^5, F_m = base + (1 - base) (1 - |v.h|)^5
  D: GGX, alpha = roughness^2 (at least 1e-3, as igi); V = G2 / (4 |n.l| |n.v|),
  G2 height-correlated (the specification's V in its own form).

Properties: base_color (texture), metallic and roughness (1-channel textures,
the factors already multiplied in), f0 (rgb) and weight (float). Sampling
picks Mitsuba's GGX visible normals or the cosine lobe with the probability
of the GGX lobe's share estimated at the view (within [0.1, 0.9]); its pdf
is the mixture. One-sided: wrap it in "twosided".
"""
import drjit as dr
import mitsuba as mi

MIN_ALPHA = 1e-3


def _schlick(cos_theta):
    m = dr.clip(1.0 - cos_theta, 0.0, 1.0)
    return (m * m) * (m * m) * m


def _texture(value):
    """A texture property, or a constant (an rgb or float property) as a texture."""
    if isinstance(value, mi.Texture):
        return value
    if isinstance(value, (int, float)):
        return mi.load_dict({"type": "uniform", "value": float(value)})
    return mi.load_dict({"type": "rgb", "value": [float(c) for c in value]})


class GltfMetallicRoughness(mi.BSDF):
    def __init__(self, props):
        mi.BSDF.__init__(self, props)
        self.base = _texture(props["base_color"])
        self.metallic = _texture(props["metallic"])
        self.roughness = _texture(props["roughness"])
        self.f0 = mi.Color3f(props["f0"]) if props.has_property("f0") else mi.Color3f(0.04)
        self.weight = props.get("weight", 1.0)
        diffuse = mi.BSDFFlags.DiffuseReflection | mi.BSDFFlags.FrontSide
        glossy = mi.BSDFFlags.GlossyReflection | mi.BSDFFlags.FrontSide
        self.m_components = [diffuse, glossy]
        self.m_flags = diffuse | glossy

    def _point(self, si):
        base = self.base.eval(si)
        metallic = dr.clip(self.metallic.eval_1(si), 0.0, 1.0)
        roughness = self.roughness.eval_1(si)
        return base, metallic, dr.maximum(roughness * roughness, MIN_ALPHA)

    def _weights(self, base, metallic, s):
        """(diffuse weight, GGX lobe's Fresnel) at Schlick weight s."""
        dielectric = self.f0 + (1.0 - self.f0) * s
        metal = base + (1.0 - base) * s
        diffuse = (1.0 - metallic) * (1.0 - self.weight * dr.max(dielectric))
        return diffuse, (1.0 - metallic) * self.weight * dielectric + metallic * metal

    def _specular_probability(self, base, metallic, cos_o):
        diffuse, specular = self._weights(base, metallic, _schlick(cos_o))
        d, s = diffuse * dr.mean(base), dr.mean(specular)
        p = dr.clip(s / (s + d), 0.1, 0.9)
        return dr.select(d > 0.0, dr.select(s > 0.0, p, 0.0), 1.0)

    def _value_pdf(self, si, wo):
        base, metallic, alpha = self._point(si)
        wi = si.wi
        cos_i, cos_o = mi.Frame3f.cos_theta(wo), mi.Frame3f.cos_theta(wi)
        valid = (cos_i > 0.0) & (cos_o > 0.0)
        h = dr.normalize(wi + wo)
        diffuse, specular = self._weights(base, metallic, _schlick(dr.abs(dr.dot(wi, h))))
        a2 = alpha * alpha
        d = a2 / (dr.pi * dr.square(h.z * h.z * (a2 - 1.0) + 1.0))
        v = 0.5 / (cos_i * dr.sqrt(cos_o * cos_o * (1.0 - a2) + a2) + cos_o * dr.sqrt(cos_i * cos_i * (1.0 - a2) + a2))
        value = (diffuse * dr.inv_pi) * base + specular * (d * v)
        distribution = mi.MicrofacetDistribution(mi.MicrofacetType.GGX, alpha, True)
        pdf_ggx = distribution.pdf(wi, h) / (4.0 * dr.abs(dr.dot(wo, h)))
        q = self._specular_probability(base, metallic, cos_o)
        pdf = q * pdf_ggx + (1.0 - q) * cos_i * dr.inv_pi
        return dr.select(valid, value * cos_i, 0.0), dr.select(valid, pdf, 0.0)

    def sample(self, ctx, si, sample1, sample2, active=True):
        base, metallic, alpha = self._point(si)
        cos_o = mi.Frame3f.cos_theta(si.wi)
        specular = sample1 < self._specular_probability(base, metallic, cos_o)
        distribution = mi.MicrofacetDistribution(mi.MicrofacetType.GGX, alpha, True)
        m, _ = distribution.sample(si.wi, sample2)
        wo = dr.select(specular, mi.reflect(si.wi, m), mi.warp.square_to_cosine_hemisphere(sample2))
        value, pdf = self._value_pdf(si, wo)
        bs = mi.BSDFSample3f()
        bs.wo = wo
        bs.pdf = pdf
        bs.eta = 1.0
        bs.sampled_component = dr.select(specular, 1, 0)
        bs.sampled_type = dr.select(specular, mi.UInt32(+mi.BSDFFlags.GlossyReflection),
                                    mi.UInt32(+mi.BSDFFlags.DiffuseReflection))
        ok = (cos_o > 0.0) & (pdf > 0.0)
        return bs, dr.select(ok, value / dr.select(ok, pdf, 1.0), 0.0)

    def eval(self, ctx, si, wo, active=True):
        return self._value_pdf(si, wo)[0]

    def pdf(self, ctx, si, wo, active=True):
        return self._value_pdf(si, wo)[1]

    def eval_pdf(self, ctx, si, wo, active=True):
        return self._value_pdf(si, wo)

    def traverse(self, callback):
        pass

    def parameters_changed(self, keys):
        pass

    def to_string(self):
        return "GltfMetallicRoughness[]"


mi.register_bsdf("gltf_metallic_roughness", lambda props: GltfMetallicRoughness(props))
