//! The split-sum BRDF lookup table: its data type, its texel convention and the
//! quadrature tables that both backends integrate it with.
//!
//! # What the LUT holds
//! For n·v and roughness r, with F = F0 (1 − Fc) + Fc and Fc = (1 − v·h)⁵ (Karis 2013):
//!
//! A = ∫ f/F · (1 − Fc) (n·l) dl,   B = ∫ f/F · Fc (n·l) dl,
//!
//! so that ∫ f (n·l) dl = F0·A + B. Texel (i, j) of a W×H table holds n·v = (i + ½)/W and
//! r = (j + ½)/H; row 0 (roughness ≈ 0) is stored first (docs/conventions.md, "BRDF LUT").
//!
//! # How it is integrated (deterministic quadrature, not Monte Carlo)
//! Substituting the GGX half-vector density pdf(h) = D (n·h) turns each integral into
//! ∫₀¹ dq ∫₀^π dφ/π · G1(n·l) · G1(n·v)/(n·v) · (v·h)/(n·h) · {1 − Fc, Fc}
//! where q is the GGX CDF variable of θ_h (see `math::sampling`). The integrand is smooth
//! except where l crosses the horizon. With v = (sin θv, 0, cos θv), n·l ≥ 0 for every φ
//! when θh ≤ (π/2 − θv)/2, for no φ when θh ≥ (π/2 + θv)/2, and in between for
//! cos φ ≥ cos θv (1 − 2cos²θh) / (2 sin θv sin θh cos θh). So the θh range is split into
//! "full" panels (two: [0, θ₁/g] and [θ₁/g, θ₁], θ₁ the first breakpoint, g the panel
//! growth, because the integrand varies quickly just below θ₁ where l nears the horizon at
//! φ = π) and "partial" panels whose φ range ends exactly on the horizon. The φ range
//! changes on the scale of θh near the first breakpoint (π/2 − θv)/2 and of π/2 − θh near
//! the second, both tiny at grazing n·v, so partial panels grow geometrically away from
//! both breakpoints (mirror images about π/4), and the panels touching them use
//! a quadratic change of variable that removes the square-root behaviour of the φ range
//! there. Each panel is integrated with Gauss-Legendre in q and in φ. G1(n·v)/(n·v) is
//! divided out analytically, so the grazing column is as accurate as the rest.
//! Measured against an adaptive f64 integral (tests/lut_accuracy.rs): max |error| 5.4e-5
//! over every 8th texel and every edge texel of 512², grazing column and roughness ≈ 0
//! and ≈ 1 included (bar 1e-4).

/// Edge of the LUT `splitsum lut` and `bake` write by default.
pub const DEFAULT_LUT_SIZE: u32 = 512;

use crate::math::quadrature::{gauss_legendre_even_half, gauss_legendre_unit, Node};

// The rule sizes below trade accuracy for time, measured by `quadrature_scan` in
// tests/lut_accuracy.rs (worst |error| over the check texels of 512², CPU seconds of a
// 512² table): 12/8/6 nodes with growth 2.5 give 1.2e-5 in 0.50 s; 10/6/5 with growth 3
// give 3.8e-5 (2.6× inside the 1e-4 bar, 37× better than 1024-sample Monte Carlo) in
// 0.32 s, and are the default; 10/5/5 reach 1.0e-4.

/// Gauss-Legendre nodes in q for the full panel (θh below the first horizon breakpoint).
pub const FULL_PANEL_NODES: usize = 10;
/// Gauss-Legendre nodes in q for each partial panel.
pub const PARTIAL_PANEL_NODES: usize = 6;
/// Nodes in φ within every panel: the integrand is even in φ, so the rule is the positive
/// half of a 2n-point Gauss-Legendre rule on [−φmax, φmax] (see
/// [`gauss_legendre_even_half`]).
pub const PHI_NODES: usize = 5;
/// Geometric growth of partial panels away from the two breakpoints (see
/// `cpu::brdf_lut::next_panel_end`).
pub const PANEL_GROWTH: f32 = 3.0;
/// At most this many partial panels per texel (growth 3 needs about 2·log₃(π/2 / n·v) of
/// them: 19 at n·v = 1/16384; the last panel always ends at the second breakpoint).
pub const MAX_PARTIAL_PANELS: u32 = 64;

/// Spacing, in texels, of the grid the CPU integrates exactly before interpolating the
/// texels between (`cpu::lut_interpolation`), along n·v and along roughness. The table is
/// smoother along roughness: measured on 512² (`interpolated_lut_matches_every_texel_
/// integrated`), steps (4, 4) integrate 15.5 % of the default model's texels, (4, 8)
/// 9.6 %, (8, 8) 11.1 %, (8, 4) 13.9 % and (4, 16) 14.0 % (more cells fail their check),
/// all within 1.9e-5 of integrating every texel.
pub const LUT_COARSE_STEP: [u32; 2] = [4, 8];

/// Largest interpolation error, relative to max(1, |value|), that a coarse cell's check
/// texel may show before the whole cell is integrated exactly: a tenth of the 1e-4 bar,
/// leaving room for the quadrature's own 5.4e-5 and for texels of a cell that interpolate
/// worse than its middle.
pub const LUT_INTERPOLATION_TOLERANCE: f32 = 1e-5;

/// Largest LUT edge accepted (per side).
pub const MAX_LUT_SIZE: u32 = 8192;

/// The visibility term V of a LUT's integrand f = D V F with GGX D (α = r²).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Visibility {
    /// Separable Smith with Schlick-GGX G1, k = r²/2 (Karis 2013): V = G1(l) G1(v) / (4 n·l n·v).
    SchlickGgx = 0,
    /// Height-correlated Smith-GGX (Heitz 2014): V = 0.5 / (n·l Λ'(v) + n·v Λ'(l)), what
    /// Filament, three.js and the glTF Sample Viewer use.
    SmithCorrelated = 1,
    /// Ashikhmin / Neubelt (Neubelt & Pettineo 2013): V = 1 / (4 (n·l + n·v − n·l n·v)),
    /// the sheen visibility of Filament's cloth and glTF-IBL-Sampler's Charlie LUT.
    Ashikhmin = 2,
    /// KHR_materials_sheen's V = clamp(1 / ((1 + Λ(v) + Λ(l)) 4 n·v n·l), 0, 1) with the
    /// fitted Charlie Λ (Estevez & Kulla 2017), the glTF Sample Viewer's `V_Sheen`.
    Sheen = 3,
}

/// The microfacet distribution D of a LUT's integrand (the quadrature runs in its CDF).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LutDistribution {
    /// GGX / Trowbridge-Reitz, α = r².
    Ggx = 0,
    /// Charlie sheen (Estevez & Kulla 2017), α = r²: D = (2 + 1/α) sin^(1/α)θ / (2π).
    Charlie = 1,
}

/// How a LUT stores its two integrals A = ∫ f/F (1 − Fc)(n·l) and B = ∫ f/F Fc (n·l).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LutLayout {
    /// (A, B): specular ≈ prefiltered · (F0·A + B) (Karis 2013).
    ScaleBias = 0,
    /// (B, A + B) = (∫ Fc V', ∫ V'), Filament's `DFV_Multiscatter` (Karis 2014, Fdez-Agüera
    /// 2019): specular ≈ prefiltered · mix(x, y, F0), and the multiple-scattering energy
    /// compensation is 1 + F0 (1/y − 1).
    Multiscatter = 1,
    /// (A + B, 0) = (∫ f (n·l) with F = 1, 0): a directional albedo, for models without
    /// Fresnel (the Charlie sheen LUT).
    Albedo = 2,
}

/// A LUT model: which integrand and which layout (`splitsum lut --model`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LutModel {
    /// (A, B) with Smith/Schlick-GGX, k = r²/2: the default, the mission's model.
    #[default]
    SchlickGgx,
    /// (A, B) with the height-correlated Smith visibility.
    SmithCorrelated,
    /// (∫ Fc V', ∫ V') with Smith/Schlick-GGX.
    MultiscatterSchlickGgx,
    /// (∫ Fc V', ∫ V') with the height-correlated Smith visibility: Filament's DFG (its R
    /// and G channels).
    MultiscatterSmithCorrelated,
    /// (E, 0), E = ∫ D_Charlie V_Ashikhmin (n·l) dl: the sheen LUT of Filament's cloth DFG
    /// (its B channel, `DFV_Charlie_Uniform`) and glTF-IBL-Sampler's `lut_charlie` (B).
    Charlie,
    /// (E, 0), E = ∫ D_Charlie V_Sheen (n·l) dl: the directional albedo of the
    /// KHR_materials_sheen BRDF, the quantity of the glTF Sample Viewer's `lut_sheen_E`
    /// (its R), which scales the base layer by 1 − max(sheen colour)·E.
    SheenAlbedo,
    /// Filament's three-channel DFG (cmgen `--ibl-dfg-multiscatter --ibl-dfg-cloth`):
    /// R, G as [`LutModel::MultiscatterSmithCorrelated`] and B the cloth albedo of
    /// [`LutModel::Charlie`], one table in one file ([`BrdfLut::third`]).
    FilamentDfg,
}

impl LutModel {
    /// Every model, in the command line's order.
    pub const ALL: [LutModel; 7] = [
        LutModel::SchlickGgx,
        LutModel::SmithCorrelated,
        LutModel::MultiscatterSchlickGgx,
        LutModel::MultiscatterSmithCorrelated,
        LutModel::Charlie,
        LutModel::SheenAlbedo,
        LutModel::FilamentDfg,
    ];

    /// Every model that is one integrand (all but [`LutModel::FilamentDfg`], which
    /// combines two of them), in the command line's order.
    pub fn singles() -> impl Iterator<Item = LutModel> {
        Self::ALL.into_iter().filter(|m| m.parts().1.is_none())
    }

    /// The one-integrand models a table of this model is made of: the model itself for
    /// the two channels (R, G), and the model whose first channel becomes a third (B).
    pub fn parts(self) -> (LutModel, Option<LutModel>) {
        match self {
            LutModel::FilamentDfg => (
                LutModel::MultiscatterSmithCorrelated,
                Some(LutModel::Charlie),
            ),
            m => (m, None),
        }
    }

    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            LutModel::SchlickGgx => "schlick-ggx",
            LutModel::SmithCorrelated => "smith-correlated",
            LutModel::MultiscatterSchlickGgx => "multiscatter-schlick-ggx",
            LutModel::MultiscatterSmithCorrelated => "multiscatter-smith-correlated",
            LutModel::Charlie => "charlie",
            LutModel::SheenAlbedo => "sheen-albedo",
            LutModel::FilamentDfg => "filament-dfg",
        }
    }

    /// The model called `name` ([`LutModel::name`]).
    pub fn by_name(name: &str) -> Option<LutModel> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }

    /// What the channels hold, in a line.
    pub fn description(self) -> &'static str {
        match self {
            LutModel::SchlickGgx => "(A, B) scale and bias, Smith/Schlick-GGX with k = r²/2 (Karis 2013)",
            LutModel::SmithCorrelated => "(A, B) with the height-correlated Smith visibility (Heitz 2014)",
            LutModel::MultiscatterSchlickGgx => "(∫Fc·V, ∫V), Schlick-GGX: specular = mix(x, y, f0), energy compensation 1 + f0 (1/y − 1)",
            LutModel::MultiscatterSmithCorrelated => "(∫Fc·V, ∫V), height-correlated Smith: Filament's DFG (R, G)",
            LutModel::Charlie => "(E, 0): the Charlie sheen albedo with the Ashikhmin visibility (Filament's cloth DFG channel, glTF-IBL-Sampler's lut_charlie); exceeds 1 near grazing: use .exr or .ktx2",
            LutModel::SheenAlbedo => "(E, 0): the KHR_materials_sheen albedo (Charlie D, V_Sheen), the glTF Sample Viewer's lut_sheen_E quantity",
            LutModel::FilamentDfg => "Filament's three-channel DFG: R, G as multiscatter-smith-correlated, B the cloth albedo as charlie (cmgen --ibl-dfg-multiscatter --ibl-dfg-cloth)",
        }
    }

    /// The distribution (of the R, G channels).
    pub fn distribution(self) -> LutDistribution {
        match self.parts().0 {
            LutModel::Charlie | LutModel::SheenAlbedo => LutDistribution::Charlie,
            _ => LutDistribution::Ggx,
        }
    }

    /// The visibility term (of the R, G channels).
    pub fn visibility(self) -> Visibility {
        match self.parts().0 {
            LutModel::SchlickGgx | LutModel::MultiscatterSchlickGgx => Visibility::SchlickGgx,
            LutModel::Charlie => Visibility::Ashikhmin,
            LutModel::SheenAlbedo => Visibility::Sheen,
            _ => Visibility::SmithCorrelated,
        }
    }

    /// The layout of the R, G channels.
    pub fn layout(self) -> LutLayout {
        match self.parts().0 {
            LutModel::SchlickGgx | LutModel::SmithCorrelated => LutLayout::ScaleBias,
            LutModel::Charlie | LutModel::SheenAlbedo => LutLayout::Albedo,
            _ => LutLayout::Multiscatter,
        }
    }
}

impl LutLayout {
    /// The stored pair for the integrals (A, B).
    pub fn arrange(self, ab: [f32; 2]) -> [f32; 2] {
        match self {
            LutLayout::ScaleBias => ab,
            LutLayout::Multiscatter => [ab[1], ab[0] + ab[1]],
            LutLayout::Albedo => [ab[0] + ab[1], 0.0],
        }
    }

    /// The integrals (A, B) of a stored pair, where the layout holds both (`None` for
    /// [`LutLayout::Albedo`], which keeps only their sum).
    pub fn scale_bias(self, stored: [f32; 2]) -> Option<[f32; 2]> {
        match self {
            LutLayout::ScaleBias => Some(stored),
            LutLayout::Multiscatter => Some([stored[1] - stored[0], stored[0]]),
            LutLayout::Albedo => None,
        }
    }
}

/// A BRDF lookup table: `data[j * width + i]` holds the model's two channels (for the
/// default, [A, B]) for n·v = (i + ½)/width and roughness = (j + ½)/height.
#[derive(Clone, Debug, PartialEq)]
pub struct BrdfLut {
    /// Number of n·v columns.
    pub width: u32,
    /// Number of roughness rows.
    pub height: u32,
    /// Row-major channel pairs ([`LutModel`]); row 0 is roughness ≈ 0.
    pub data: Vec<[f32; 2]>,
    /// A third channel (B), row-major like `data`, for models that have one (Filament's
    /// cloth albedo in [`LutModel::FilamentDfg`]); `None` for two-channel models.
    pub third: Option<Vec<f32>>,
    /// The model the table integrates.
    pub model: LutModel,
}

impl BrdfLut {
    /// A two-channel table of the default model (see [`BrdfLut::assemble`] for others).
    pub fn new(width: u32, height: u32, data: Vec<[f32; 2]>) -> Self {
        BrdfLut {
            width,
            height,
            data,
            third: None,
            model: LutModel::default(),
        }
    }

    /// The table of `model` from `single`, which computes one-integrand tables: its (R, G)
    /// table, and for a model with a third channel that channel from its part's first.
    pub fn assemble(
        model: LutModel,
        mut single: impl FnMut(LutModel) -> crate::Result<BrdfLut>,
    ) -> crate::Result<BrdfLut> {
        let (rg, b) = model.parts();
        let mut lut = single(rg)?;
        if let Some(b) = b {
            lut.third = Some(single(b)?.data.iter().map(|t| t[0]).collect());
        }
        lut.model = model;
        Ok(lut)
    }

    /// Every stored value, all channels.
    pub fn values(&self) -> impl Iterator<Item = f32> + '_ {
        self.data
            .iter()
            .flatten()
            .copied()
            .chain(self.third.iter().flatten().copied())
    }

    /// The (A, B) pair at column `i` (n·v) and row `j` (roughness).
    pub fn get(&self, i: u32, j: u32) -> [f32; 2] {
        self.data[(j * self.width + i) as usize]
    }
}

/// n·v and roughness at the centre of LUT texel (i, j) of a width×height table.
pub fn lut_texel_coords(i: u32, j: u32, width: u32, height: u32) -> (f32, f32) {
    (
        (i as f32 + 0.5) / width as f32,
        (j as f32 + 0.5) / height as f32,
    )
}

/// Checks a LUT size requested by the user.
pub fn validate_lut_size(width: u32, height: u32) -> crate::Result<()> {
    for (name, v) in [("width", width), ("height", height)] {
        if v == 0 || v > MAX_LUT_SIZE {
            return Err(crate::Error::InvalidOption {
                option: "size",
                message: format!("a LUT {name} of {v} is not from 1 to {MAX_LUT_SIZE}"),
            });
        }
    }
    Ok(())
}

/// Where one Gauss-Legendre rule sits inside [`LutQuadrature::nodes`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RuleRange {
    /// Index of the rule's first node.
    pub offset: u32,
    /// Number of nodes.
    pub count: u32,
}

/// The quadrature tables and panel parameters used by both LUT backends. The GPU kernel
/// receives exactly these numbers (nodes in a storage buffer, the rest in [`LutParams`]).
#[derive(Clone, Debug)]
pub struct LutQuadrature {
    /// All rules' (x, w) pairs on [0, 1], concatenated.
    pub nodes: Vec<[f32; 2]>,
    /// Rule in q for the full panel.
    pub full: RuleRange,
    /// Rule in q for each partial panel.
    pub partial: RuleRange,
    /// Rule in φ.
    pub phi: RuleRange,
    /// Geometric growth of partial panels in θh.
    pub panel_growth: f32,
    /// Maximum number of partial panels.
    pub max_panels: u32,
}

impl Default for LutQuadrature {
    fn default() -> Self {
        Self::with_rules(
            FULL_PANEL_NODES,
            PARTIAL_PANEL_NODES,
            PHI_NODES,
            PANEL_GROWTH,
        )
    }
}

/// Rules of the Charlie model: its albedo reaches 22 near grazing n·v and varies faster
/// there (the 1/(n·h) of the half-vector Jacobian where the distribution's mass lies flat),
/// so the 10/6/5 rules leave 1.2e-4 relative error; 12/8/6 with growth 2.5 bring it within
/// 1e-4 (tests/lut_accuracy.rs).
pub const CHARLIE_RULES: (usize, usize, usize, f32) = (12, 8, 6, 2.5);

/// Rules of the sheen-albedo model: its fitted Λ(n·l) grows like exp(a / (1 + b (n·l)^0.19))
/// towards the horizon, which ends each φ range, so φ needs more nodes: the Charlie rules
/// leave 9e-4, 12/8/12 leave 7e-5, 16/12/16 with growth 2 leave 4e-5 at the worst texels
/// tried (tests/lut_accuracy.rs).
pub const SHEEN_RULES: (usize, usize, usize, f32) = (16, 12, 16, 2.0);

impl LutQuadrature {
    /// The tables `model` is integrated with: the defaults, [`CHARLIE_RULES`] or
    /// [`SHEEN_RULES`].
    pub fn for_model(model: LutModel) -> Self {
        let (full, partial, phi, growth) = match model.parts().0 {
            LutModel::Charlie => CHARLIE_RULES,
            LutModel::SheenAlbedo => SHEEN_RULES,
            _ => return Self::default(),
        };
        Self::with_rules(full, partial, phi, growth)
    }

    /// Tables with `full` and `partial` Gauss-Legendre nodes in q, `phi` nodes in φ and
    /// partial panels growing by `growth` (the default uses the constants above; other
    /// values are for accuracy-versus-cost studies).
    pub fn with_rules(full: usize, partial: usize, phi: usize, growth: f32) -> Self {
        let mut nodes = Vec::new();
        let mut push = |rule: Vec<Node>| {
            let offset = nodes.len() as u32;
            let count = rule.len() as u32;
            nodes.extend(rule.into_iter().map(|q| [q.x as f32, q.w as f32]));
            RuleRange { offset, count }
        };
        let full = push(gauss_legendre_unit(full));
        let partial = push(gauss_legendre_unit(partial));
        let phi = push(gauss_legendre_even_half(phi));
        LutQuadrature {
            nodes,
            full,
            partial,
            phi,
            panel_growth: growth,
            max_panels: MAX_PARTIAL_PANELS,
        }
    }

    /// The (x, w) pairs of one rule.
    pub fn rule(&self, r: RuleRange) -> &[[f32; 2]] {
        &self.nodes[r.offset as usize..(r.offset + r.count) as usize]
    }

    /// The uniform block the GPU kernel reads, for a width×height table of `model`.
    pub fn params(&self, width: u32, height: u32, model: LutModel) -> LutParams {
        LutParams {
            size: [width, height],
            full_rule: [self.full.offset, self.full.count],
            partial_rule: [self.partial.offset, self.partial.count],
            phi_rule: [self.phi.offset, self.phi.count],
            panel_growth: self.panel_growth,
            max_panels: self.max_panels,
            visibility: model.visibility() as u32,
            channel_layout: model.layout() as u32,
            distribution: model.distribution() as u32,
            _pad: [0; 3],
        }
    }
}

/// Uniform block of `shaders/brdf_lut.wgsl` (`struct LutParams`); a test checks that the
/// WGSL member offsets equal these fields' offsets.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct LutParams {
    /// Table width (n·v) and height (roughness).
    pub size: [u32; 2],
    /// (offset, count) of the full-panel rule.
    pub full_rule: [u32; 2],
    /// (offset, count) of the partial-panel rule.
    pub partial_rule: [u32; 2],
    /// (offset, count) of the φ rule.
    pub phi_rule: [u32; 2],
    /// Geometric growth of partial panels.
    pub panel_growth: f32,
    /// Maximum number of partial panels.
    pub max_panels: u32,
    /// [`Visibility`] as u32.
    pub visibility: u32,
    /// [`LutLayout`] as u32 (`layout` is a reserved word in WGSL).
    pub channel_layout: u32,
    /// [`LutDistribution`] as u32.
    pub distribution: u32,
    /// Pads the block to 16 bytes as uniform buffers require.
    pub _pad: [u32; 3],
}
