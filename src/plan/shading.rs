//! How a shader turns a bake's files into light: which LUT it reads and how it combines the
//! prefiltered radiance, the LUT's (A, B) and the irradiance ([`IblTerms`]), where its
//! diffuse light comes from ([`IrradianceSource`]), and the BRDF it shades lights with
//! ([`LightBrdf`]). The README's recipe is [`Shading::GENERIC`]; each engine target carries
//! its engine's own (`targets::*`, read in the engine's shader source), so the preview can
//! shade spheres as that engine does and measure them against the integral of that same
//! engine's BRDF over the environment (what the engine would show if the environment were
//! lit by its own lights, texel by texel).
//!
//! Per channel, with S the prefiltered radiance along the lookup, (A, B) the LUT at
//! (n·v, r), E the irradiance E/π at n, c the albedo, m metallic and F0 the reflectance at
//! normal incidence (the metal's colour, 0.04 for the dielectric):
//!
//! - kS = F0, or with `roughness_fresnel` F0 + (max(1 − r, F0) − F0)(1 − n·v)⁵ (Fdez-Agüera
//!   2019, listing 2; the glTF Sample Viewer's and Bevy's `k_S`);
//! - FssEss = kS A + B, Ess = A + B, Ems = 1 − Ess, Favg = F0 + (1 − F0)/21 and
//!   FmsEms = Ems FssEss Favg / (1 − Ems Favg) (Fdez-Agüera 2019, eq. 15–17: the light
//!   scattered more than once between microfacets, which a single-scattering BRDF loses).

use crate::math::brdf::env_brdf_approx;
use crate::math::lookup::SpecularLookup;
use crate::plan::lut::{lut_texel_coords, BrdfLut, LutModel};

/// The cosine-weighted hemispherical mean of the Fresnel-Schlick weight (1 − cos θ)⁵,
/// 2 ∫ (1 − μ)⁵ μ dμ = 1/21: Favg = F0 + (1 − F0)/21 (Fdez-Agüera 2019, eq. 17; the 1/21
/// in three.js's, the glTF Sample Viewer's and Bevy's shaders).
pub const FRESNEL_MEAN_WEIGHT: f32 = 1.0 / 21.0;

/// How the shader combines S, (A, B) and E into the split-sum's specular and diffuse light
/// (the module's notation). The value is the kernels' code (`IBL_TERMS_*` in
/// `shaders/common/split_sum.wgsl`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u32)]
pub enum IblTerms {
    /// The README's recipe: S (F0 A + B) + E c (1 − F0)(1 − W(n·v))(1 − m), W the BRDF's
    /// diffuse Fresnel weight under uniform light (`brdf::diffuse_fresnel_weight`).
    Splitsum = 0,
    /// Filament: S FssEss (1 + F0 (1/Ess − 1)) + E c (1 − FssEss)(1 − m): the specular
    /// scaled by the energy its single scattering loses (Kulla & Conty 2017 as Filament's
    /// `energyCompensation`), the diffuse by what the specular leaves.
    EnergyCompensated = 1,
    /// three.js and Bevy: S FssEss + E FmsEms + E c (1 − FssEss − FmsEms)(1 − m): the
    /// multiple scattering lit by the irradiance.
    MultiscatterIrradiance = 2,
    /// The glTF Sample Viewer: S (FssEss + FmsEms) + E c (1 − FssEss − FmsEms)(1 − m): the
    /// multiple scattering lit by the prefiltered radiance.
    MultiscatterRadiance = 3,
    /// Babylon.js: S FssEss (1 + F0 (1/Ess − 1)) + E c (1 − F0)(1 − m): Filament's
    /// compensation of the specular, and the diffuse weighted by the dielectric's 1 − F0
    /// whatever the specular takes (`LEGACY_SPECULAR_ENERGY_CONSERVATION`; the preview's
    /// materials are metal, m = 1, or dielectric, m = 0, so their F0 is the dielectric's
    /// wherever the diffuse counts).
    LegacyDiffuse = 4,
}

/// How far the shader blends the prefiltered radiance S toward the irradiance E/π at n
/// before it combines them, S ← mix(S, E, w(r)): a wide lobe reads what the cosine lobe
/// at n reads, where the chain's lobe along the lookup reaches below the horizon. The
/// value is the kernels' code (`RADIANCE_BLEND_*` in `shaders/common/split_sum.wgsl`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u32)]
pub enum RadianceBlend {
    /// S as read.
    None = 0,
    /// w = α = r² (Babylon.js's `MIX_IBL_RADIANCE_WITH_IRRADIANCE`).
    Alpha = 1,
    /// w = α² = r⁴ (the README's recipe; docs/accuracy.md, "The chain's layout and the
    /// blend toward E/π": chosen on quarry_01 against w = α, which leans too far at mid
    /// roughness, and checked on the other bundled HDRIs).
    AlphaSquared = 2,
}

impl RadianceBlend {
    /// The weight w of E/π for roughness `r`.
    pub fn weight(self, r: f32) -> f32 {
        let alpha = r * r;
        match self {
            RadianceBlend::None => 0.0,
            RadianceBlend::Alpha => alpha,
            RadianceBlend::AlphaSquared => alpha * alpha,
        }
    }
}

/// The split-sum LUT a shader reads, as (A, B) at (n·v, r).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ShaderLut {
    /// A table of a LUT model ((A, B), or Filament's (B, A + B), rearranged): the engine's
    /// own of `size`² where it ships one (three.js's 16²), the bake's or the preview's
    /// [`DEFAULT_LUT_SIZE`](crate::plan::lut::DEFAULT_LUT_SIZE)² otherwise (`None`).
    Table {
        /// The model.
        model: LutModel,
        /// The engine's own edge.
        size: Option<u32>,
    },
    /// Karis's analytic fit of (A, B) for mobile (`brdf::env_brdf_approx`; Bevy's `F_AB`
    /// without its `dfg_lut` feature), tabulated at the preview's LUT size.
    EnvBrdfApprox,
}

/// How a shader combines the split-sum's reads (what the kernels take of a [`Shading`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShadingTerms {
    /// The combination.
    pub ibl: IblTerms,
    /// Whether kS is the roughness-aware Fresnel (the module's kS).
    pub roughness_fresnel: bool,
    /// How far S is blended toward E/π first.
    pub radiance_blend: RadianceBlend,
}

impl ShadingTerms {
    /// The README's recipe.
    pub const GENERIC: ShadingTerms = ShadingTerms {
        ibl: IblTerms::Splitsum,
        roughness_fresnel: false,
        radiance_blend: RadianceBlend::AlphaSquared,
    };
}

/// Where the shader's diffuse light E/π comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IrradianceSource {
    /// The bake's irradiance cube, read bilinearly at n.
    Cube,
    /// The specular chain's last level, read bilinearly at n (three.js's
    /// `textureLod(envMap, n, ENVMAP_MAX_LOD)`, Filament's `Irradiance_RoughnessOne`
    /// without SH): the bake fits that level to E/π.
    LastLevel,
}

/// The masking-shadowing term of a light's specular BRDF (of the LUT models' visibilities,
/// `plan::lut::Visibility`, the two a light's BRDF uses). The value is the kernels' code
/// (`MASKING_*` in `shaders/common/material.wgsl`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u32)]
pub enum Masking {
    /// G = G1(l) G1(v), Schlick-GGX with k = α/2 (the README's recipe and its LUT).
    SchlickGgx = 0,
    /// The height-correlated Smith G2 = 1 / (1 + Λ(v) + Λ(l)) (Heitz 2014; three.js's
    /// `V_GGX_SmithCorrelated`, Filament's `V_SmithGGXCorrelated`, the glTF Sample
    /// Viewer's `V_GGX`).
    SmithCorrelated = 1,
}

/// How a light's diffuse lobe is weighted. The value is the kernels' code (`DIFFUSE_*` in
/// `shaders/common/material.wgsl`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u32)]
pub enum DiffuseLobe {
    /// Lambert c/π × (1 − F(v·h))(1 − m): the light the specular interface reflects is not
    /// diffused (the recipe's, three.js's and the glTF Sample Viewer's `fresnel_mix`).
    FresnelWeighted = 0,
    /// Lambert c/π × (1 − m), whatever the specular reflects (Filament's `Fd_Lambert`).
    Lambert = 1,
    /// Burley's diffuse (`brdf::burley_weight` × c/π) × (1 − m), unweighted by F (bevy_pbr's
    /// `Fd_Burley`).
    Burley = 2,
    /// Lambert c/π × (1 − F0)(1 − m), the reflectance at normal incidence taken off
    /// whatever F(v·h) is (Babylon.js's legacy energy conservation of `surfaceAlbedo`; its
    /// default E-Oren-Nayar diffuse is Lambert at its default diffuse roughness 0).
    DielectricLambert = 3,
}

/// The BRDF a shader lights with: GGX D (α = r²) and Fresnel-Schlick, with these terms.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LightBrdf {
    /// The specular masking-shadowing.
    pub masking: Masking,
    /// The diffuse weighting.
    pub diffuse: DiffuseLobe,
    /// Whether the specular is scaled by 1 + F0 (1/Ess − 1), Ess = A + B of the shader's
    /// LUT at (n·v, r): the energy multiple scattering returns (Turquin 2019; three.js's
    /// `multiScatteringCompensation`, Filament's `energyCompensation`).
    pub compensated: bool,
}

impl LightBrdf {
    /// The README's BRDF, the preview's ground truth for the recipe.
    pub const GENERIC: LightBrdf = LightBrdf {
        masking: Masking::SchlickGgx,
        diffuse: DiffuseLobe::FresnelWeighted,
        compensated: false,
    };
}

/// A shader's whole model: what the preview shades spheres with in a target's mode.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shading {
    /// Who shades this way, for captions and tables.
    pub name: &'static str,
    /// Where the shader reads the specular chain.
    pub lookup: SpecularLookup,
    /// The smallest perceptual roughness the shader uses (it clamps r up to it for the
    /// lookup, the LUT and the lights alike).
    pub min_roughness: f32,
    /// The LUT the shader reads.
    pub lut: ShaderLut,
    /// How S, (A, B) and E combine.
    pub terms: ShadingTerms,
    /// Where E/π comes from.
    pub irradiance: IrradianceSource,
    /// The BRDF of the lights (the sun split out), and of the ground truth.
    pub light: LightBrdf,
}

impl Shading {
    /// The README's recipe: the stretched Frostbite lookup, the `schlick-ggx` LUT, the
    /// split-sum terms with the BRDF's own diffuse weight, the irradiance cube, the
    /// Schlick-GGX BRDF with Fresnel-weighted Lambert.
    pub const GENERIC: Shading = Shading {
        name: "splitsum's recipe",
        lookup: SpecularLookup::GENERIC,
        min_roughness: 0.0,
        lut: ShaderLut::Table {
            model: LutModel::SchlickGgx,
            size: None,
        },
        terms: ShadingTerms::GENERIC,
        irradiance: IrradianceSource::Cube,
        light: LightBrdf::GENERIC,
    };

    /// This model with the chain read along `lookup` (the lookup study, `preview --lookup`):
    /// the recipe's lookup with the recipe's blend toward E/π, any other plainly, as the
    /// engines that read along it do (so `--lookup reflect` is the glTF Sample Viewer's read,
    /// not Babylon.js's blended one).
    pub const fn with_lookup(self, lookup: SpecularLookup) -> Shading {
        let radiance_blend = match lookup {
            SpecularLookup::Stretched | SpecularLookup::Filtered => RadianceBlend::AlphaSquared,
            _ => RadianceBlend::None,
        };
        Shading {
            lookup,
            terms: ShadingTerms {
                radiance_blend,
                ..self.terms
            },
            ..self
        }
    }

    /// The roughness the shader uses for a material of perceptual roughness `r`.
    pub fn roughness(&self, r: f32) -> f32 {
        r.max(self.min_roughness)
    }
    /// The model in a line, for manifests: each term as `plan::shading` names it.
    pub fn describe(&self) -> String {
        let lut = match self.lut {
            ShaderLut::Table {
                model,
                size: Some(n),
            } => format!("its {n}x{n} {} LUT", model.name()),
            ShaderLut::Table { model, size: None } => format!("the {} LUT", model.name()),
            ShaderLut::EnvBrdfApprox => "Karis's analytic (A, B) for mobile".to_string(),
        };
        let irradiance = match self.irradiance {
            IrradianceSource::Cube => "the irradiance cube",
            IrradianceSource::LastLevel => "the chain's last level",
        };
        format!(
            "lookup {}, roughness at least {}, {lut}, terms {:?}{}{}, E/pi from {irradiance}; lights with {:?} masking, {:?} diffuse{}",
            self.lookup.id(),
            self.min_roughness,
            self.terms.ibl,
            if self.terms.roughness_fresnel { " with the roughness-aware kS" } else { "" },
            match self.terms.radiance_blend {
                RadianceBlend::None => "",
                RadianceBlend::Alpha => ", the radiance blended toward E/pi by alpha",
                RadianceBlend::AlphaSquared => ", the radiance blended toward E/pi by alpha^2",
            },
            self.light.masking,
            self.light.diffuse,
            if self.light.compensated { ", compensated by 1 + F0 (1/(A + B) - 1)" } else { "" },
        )
    }
}

/// [`ShaderLut::EnvBrdfApprox`] as a `width` × `height` table at the LUT's texel centres
/// (`plan::lut::lut_texel_coords`), read bilinearly like any LUT: the fit is smooth but for
/// the kink of its min(), which a 512² table places within one texel. Recorded as the
/// `schlick-ggx` model, the integrand Karis fitted (Unreal's split-sum LUT).
pub fn env_brdf_approx_table(width: u32, height: u32) -> BrdfLut {
    let data = (0..height)
        .flat_map(|j| {
            (0..width).map(move |i| {
                let (n_dot_v, r) = lut_texel_coords(i, j, width, height);
                env_brdf_approx(r, n_dot_v)
            })
        })
        .collect();
    BrdfLut::new(width, height, data)
}

impl Default for Shading {
    fn default() -> Self {
        Shading::GENERIC
    }
}
