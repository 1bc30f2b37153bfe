//! What both viewer renderers read for one frame: the baked light ([`ViewLight`]), and
//! the uniform blocks of the kernels ([`FrameUniform`] for the G-buffer and shading
//! passes, [`PresentUniform`] for tone mapping), built in Rust once so the GPU and CPU
//! renderers cannot disagree (layouts checked in tests/shaders.rs).
//!
//! A frame is three passes: the **G-buffer** (per pixel: the world position and what it
//! is — background, object, floor — and the unit normal), the **shading** (split-sum, or
//! one more truth estimate accumulated), and the **present** pass (the mode's picture,
//! exposure, Khronos PBR Neutral, sRGB, the HUD over it).

use std::sync::Arc;

use glam::{Mat4, Vec3};

use crate::environment::sun::{Sun, SunMode, MAX_LIGHTS};
use crate::environment::texels::SourceTexel;
use crate::environment::Cubemap;
use crate::math::lookup::SpecularLookup;
use crate::math::ltc::rect_polygon;
use crate::plan::chain::SpecularChain;
use crate::plan::ltc::{LtcTable, QuadLight};
use crate::plan::lut::BrdfLut;
use crate::plan::material::{ShadeMaterial, MIN_DIRECT_ALPHA};
use crate::plan::scene::{SplitSumLight, TruthLight, MIN_N_DOT_V};
use crate::plan::shading::{LightBrdf, ShadingTerms};
use crate::stages::light::BakedEnvironment;
use crate::stages::preview::picture::{auto_exposure, luminance, HEAT_LOG10_RANGE};
use crate::stages::preview::truth_environment;
use crate::view::camera::CameraFrame;
use crate::view::scene::{
    BaseMaterial, PointLight, FIT_HALF_EXTENT, FLOOR_HALF_EXTENT, FLOOR_Y, OBJECT_CENTRE,
};
use crate::Result;

/// A frame before tone mapping, per pixel: the split-sum (radiance, surface id) and the
/// truth accumulation (radiance × points, points).
pub type HdrFrame = (Vec<[f32; 4]>, Vec<[f32; 4]>);

/// The heat map's energy-weighted mean over the object: Σ |Y_split-sum − Y_truth| / Σ
/// Y_truth over its pixels (the preview's figure of a sphere, `preview --json`'s `mean`),
/// from a frame's split-sum (radiance, surface id) and truth accumulation; None before the
/// truth has an estimate or without the object in view.
pub fn heat_mean(shaded: &[[f32; 4]], accum: &[[f32; 4]]) -> Option<f32> {
    let (mut diff, mut total) = (0.0f64, 0.0f64);
    for (s, a) in shaded.iter().zip(accum) {
        if Surface::from_id(s[3]) != Surface::Object || a[3] <= 0.0 {
            continue;
        }
        let t = luminance([a[0] / a[3], a[1] / a[3], a[2] / a[3]]) as f64;
        diff += (luminance([s[0], s[1], s[2]]) as f64 - t).abs();
        total += t;
    }
    (total > 0.0).then(|| (diff / total) as f32)
}

/// What a G-buffer pixel holds (the w of its position texel).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u32)]
pub enum Surface {
    /// Nothing: the environment.
    Background = 0,
    /// The object.
    Object = 1,
    /// The floor.
    Floor = 2,
}

impl Surface {
    /// The surface of a stored id.
    pub fn from_id(id: f32) -> Surface {
        match id.round() as u32 {
            1 => Surface::Object,
            2 => Surface::Floor,
            _ => Surface::Background,
        }
    }
}

/// What the viewer shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[repr(u32)]
pub enum Mode {
    /// The split-sum render, as an engine shows the bake.
    #[default]
    SplitSum = 0,
    /// The ground truth, accumulated while the view stands still.
    Truth = 1,
    /// |Y_split-sum − Y_truth| / Y_truth, the preview's colour scale.
    Heat = 2,
}

/// The baked light the viewer renders with (generic orientation), and the environment's
/// split for the truth.
#[derive(Clone, Debug)]
pub struct ViewLight {
    /// What the HUD calls it (the input's file name).
    pub name: String,
    /// The prefiltered specular chain (level 0: the environment).
    pub specular: Cubemap,
    /// Its layout (the lod of a roughness).
    pub chain: SpecularChain,
    /// The irradiance cube (E/π).
    pub irradiance: Cubemap,
    /// The split-sum LUT.
    pub lut: BrdfLut,
    /// The environment with its full mip chain (the truth's mirror lookups).
    pub env: Cubemap,
    /// The environment without its hot texels.
    pub cold: Cubemap,
    /// The hot texels, summed exactly by the truth.
    pub hot: Vec<SourceTexel>,
    /// The preview's default exposure of this environment (a linear scale).
    pub exposure: f32,
    /// Whether the lights were taken out of the environment (`--sun split`).
    pub sun_mode: SunMode,
    /// The lights found in the environment, the sun first (kept in it or split out).
    pub found: Vec<Sun>,
    /// The lights taken out, as the shading passes read them ([`sun_texel_table`]): one
    /// record per light for the split-sum, the environment's hot texels within each
    /// light's region for the truth, the area lights' polygons and their LTC table.
    pub sun_texels: Vec<[f32; 4]>,
    /// How many of the environment's texels in `sun_texels` the truth view integrates as
    /// the lights'.
    pub sun_cells: u32,
    /// The LTC table of the viewer's light BRDF in `sun_texels`, when an area light is
    /// split out (both renderers read it).
    pub ltc: Option<Arc<LtcTable>>,
    /// The same environment baked in the other sun mode, when that differs (an HDRI
    /// with a sun): what the viewer's U key swaps in.
    pub alternate: Option<Box<ViewLight>>,
}

/// Entries of a split-out light's record in [`ViewLight::sun_texels`] (`SPLIT_RECORD` in
/// view_sun.wgsl).
pub const SPLIT_RECORD: usize = 4;

/// The quadrilateral the viewer shades a split-out area light as: the rectangle an
/// engine's rect light draws for it ([`crate::environment::sun::RectLight`], a disc as the
/// square of its solid angle), with that rectangle's uniform radiance.
pub fn view_quad(light: &Sun) -> Option<(QuadLight, Vec3)> {
    let rect = light.rect_light()?;
    let corners = rect_polygon(
        Vec3::from(light.direction),
        Vec3::from(rect.width_axis),
        rect.half_width_deg.to_radians(),
        rect.half_height_deg.to_radians(),
    );
    Some((QuadLight::new(corners), Vec3::from(rect.radiance)))
}

/// The entries of [`ViewLight::sun_texels`] (vec4s), the sun being light 0, light k's
/// shadow map k:
///
/// 1. per light, [`SPLIT_RECORD`] entries, what the split-sum view shades (as the preview
///    does): for a directional light (unit direction, 1), (its irradiance E⊥ from that
///    direction, light index), (0, 0, LTC table entry, LTC table size) and a zero entry
///    (every record names the table, which the area lights share); for an area light, shaded as
///    [`view_quad`]'s quadrilateral ([`QuadLight`]), (its unit centre, solid angle), (its
///    uniform radiance, light index), (first corner entry, 4, LTC table entry, LTC table
///    size), (its vector form factor, 0);
/// 2. the truth's hot texels of the environment as read (`hot`) that lie within a light's
///    region ([`Sun::region_radius_deg`]), moved out of `hot`, two entries each: (unit
///    direction, solid angle), (radiance, light index): the truth integrates the light as
///    the environment holds it, each light's part through the same shadow as the split-sum's;
/// 3. the area lights' corners, counter-clockwise seen from the origin, a unit vector an
///    entry;
/// 4. when there is an area light, the LTC table of the viewer's light BRDF (`ltc`, asked
///    for only then), two entries a cell: M⁻¹'s four numbers, (A + B, B, 0, 0).
///
/// Returns the table, the count of part 2's texels and the LTC table ([`SunTexels`]).
pub fn sun_texel_table(
    lights: &[Sun],
    hot: &mut Vec<SourceTexel>,
    ltc: &mut dyn FnMut() -> Result<Arc<LtcTable>>,
) -> Result<SunTexels> {
    let owner = |t: &SourceTexel| {
        let l = Vec3::from_slice(&t.dir_omega[..3]);
        lights.iter().position(|sun| {
            let cos = l.dot(Vec3::from(sun.direction)).clamp(-1.0, 1.0);
            cos.acos().to_degrees() <= sun.region_radius_deg
        })
    };
    let mut cells = Vec::new();
    hot.retain(|t| match owner(t) {
        Some(i) => {
            cells.push(t.dir_omega);
            cells.push([t.radiance[0], t.radiance[1], t.radiance[2], i as f32]);
            false
        }
        None => true,
    });
    let quads: Vec<Option<(QuadLight, Vec3)>> = lights.iter().map(view_quad).collect();
    let table = quads.iter().any(Option::is_some).then(ltc).transpose()?;
    let mut corner = SPLIT_RECORD * lights.len() + cells.len();
    let corners = 4 * quads.iter().flatten().count();
    let ltc_entry = corner + corners;
    let ltc_size = table.as_ref().map_or(0, |t| t.size);
    let mut out = Vec::new();
    for (i, (sun, quad)) in lights.iter().zip(&quads).enumerate() {
        match quad {
            Some((q, radiance)) => {
                out.push(q.centre.extend(q.solid_angle).to_array());
                out.push([radiance.x, radiance.y, radiance.z, i as f32]);
                out.push([corner as f32, 4.0, ltc_entry as f32, ltc_size as f32]);
                out.push(q.vector_form_factor.extend(0.0).to_array());
                corner += 4;
            }
            None => {
                let e = sun.irradiance;
                out.push([sun.direction[0], sun.direction[1], sun.direction[2], 1.0]);
                out.push([e[0], e[1], e[2], i as f32]);
                out.push([0.0, 0.0, ltc_entry as f32, ltc_size as f32]);
                out.push([0.0; 4]);
            }
        }
    }
    let count = (cells.len() / 2) as u32;
    out.extend(cells);
    out.extend(
        quads
            .iter()
            .flatten()
            .flat_map(|(q, _)| q.corners.map(|v| v.extend(0.0).to_array())),
    );
    if let Some(t) = &table {
        out.extend(
            t.cells
                .iter()
                .flat_map(|c| [c.inverse, [c.norm, c.fresnel, 0.0, 0.0]]),
        );
    }
    Ok(SunTexels {
        entries: out,
        cells: count,
        ltc: table,
    })
}

/// What [`sun_texel_table`] packs: the entries, how many of them are the truth's texels of
/// the lights (two entries each), and the LTC table when an area light is split out.
pub struct SunTexels {
    /// The entries, as [`ViewLight::sun_texels`].
    pub entries: Vec<[f32; 4]>,
    /// As [`ViewLight::sun_cells`].
    pub cells: u32,
    /// As [`ViewLight::ltc`].
    pub ltc: Option<Arc<LtcTable>>,
}

impl ViewLight {
    /// The viewer's light from a bake and its LUT.
    pub fn new(
        name: impl Into<String>,
        baked: &BakedEnvironment,
        lut: BrdfLut,
        ltc: &mut dyn FnMut() -> Result<Arc<LtcTable>>,
    ) -> Result<ViewLight> {
        let (env, split) = truth_environment(baked.seen());
        let mut hot = split.hot;
        let texels = sun_texel_table(baked.split_lights(), &mut hot, ltc)?;
        Ok(ViewLight {
            name: name.into(),
            exposure: auto_exposure(baked.seen()),
            specular: baked.specular.clone(),
            chain: baked.chain,
            irradiance: baked.irradiance.clone(),
            lut,
            env,
            cold: split.rest,
            hot,
            sun_mode: baked.sun_mode,
            found: baked.lights.clone(),
            sun_texels: texels.entries,
            sun_cells: texels.cells,
            ltc: texels.ltc,
            alternate: None,
        })
    }

    /// The lights taken out of the environment, the sun first (none with the sun kept).
    pub fn split_lights(&self) -> &[Sun] {
        self.sun_mode.split_out(&self.found)
    }

    /// Whether a light split out is an area light (shaded from the LTC table that
    /// `sun_texels` then holds, its shadow soft).
    pub fn has_area_lights(&self) -> bool {
        self.split_lights().iter().any(|l| l.shape.is_some())
    }

    /// How many lights the split-sum view shades (the first part of `sun_texels`).
    pub fn sun_count(&self) -> u32 {
        self.split_lights().len() as u32
    }

    /// How many of the environment's texels the truth view integrates as the lights'
    /// (the rest of `sun_texels`).
    pub fn sun_cell_count(&self) -> u32 {
        self.sun_cells
    }

    /// A black environment, shown while the first bake runs.
    pub fn blank() -> ViewLight {
        let black = |size: u32, levels: usize| Cubemap {
            size,
            levels: (0..levels)
                .map(|m| vec![[0.0; 4]; 6 * ((size >> m).max(1) as usize).pow(2)])
                .collect(),
        };
        ViewLight {
            name: "(baking)".into(),
            specular: black(4, 3),
            chain: SpecularChain::linear(3),
            irradiance: black(4, 1),
            lut: BrdfLut {
                width: 2,
                height: 2,
                data: vec![[0.0; 2]; 4],
                third: None,
                model: Default::default(),
            },
            env: black(4, 3),
            cold: black(4, 3),
            hot: Vec::new(),
            exposure: 1.0,
            sun_mode: SunMode::Keep,
            found: Vec::new(),
            sun_texels: Vec::new(),
            sun_cells: 0,
            ltc: None,
            alternate: None,
        }
    }

    /// The chain's lod for roughness `r`.
    pub fn lod(&self, r: f32) -> f32 {
        self.chain.roughness.lod(r, self.chain.levels)
    }

    /// `base` at roughness `r` as the split-sum reads it: the chain's lod for r and the
    /// generic lookup's bend (for r and its F0) and stretch
    /// (`math::lookup::SpecularLookup::GENERIC`).
    pub fn material(&self, base: &BaseMaterial, r: f32) -> ShadeMaterial {
        let lookup = SpecularLookup::GENERIC;
        base.shade(r, self.lod(r), lookup.bend(r, base.f0()), lookup.stretch())
    }

    /// What the split-sum shading reads.
    pub fn split_sum(&self) -> SplitSumLight<'_> {
        SplitSumLight {
            specular: &self.specular,
            irradiance: &self.irradiance,
            lut: &self.lut,
            // The viewer shades as the README's recipe.
            terms: ShadingTerms::GENERIC,
            filtered: SpecularLookup::GENERIC
                .filtered()
                .then_some(self.chain.roughness),
        }
    }

    /// What the truth reads, with `points` for its quadrature.
    pub fn truth<'a>(&'a self, points: &'a [[f32; 4]]) -> TruthLight<'a> {
        TruthLight {
            env: &self.env,
            cold: &self.cold,
            hot: &self.hot,
            points,
            brdf: LightBrdf::GENERIC,
        }
    }
}

/// Uniform block of the G-buffer and shading kernels (`shaders/common/view_frame.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FrameUniform {
    /// Frame width in pixels.
    pub width: u32,
    /// Frame height in pixels.
    pub height: u32,
    /// Index of this truth estimate (seeds its quadrature rotation).
    pub truth_frame: u32,
    /// Number of point lights on.
    pub light_count: u32,
    /// Camera position, w: 1 for parallel rays.
    pub position: [f32; 4],
    /// Camera right axis, w: half extent x (tan of the half angle for a pinhole).
    pub right: [f32; 4],
    /// Camera up axis, w: half extent y.
    pub up: [f32; 4],
    /// Camera front axis, w: the smallest n·v the shading uses.
    pub front: [f32; 4],
    /// World to clip space (column-major).
    pub view_projection: [[f32; 4]; 4],
    /// The object's material: (F0, metallic), (albedo, roughness), (lod, bend, stretch, 0).
    pub object: [[f32; 4]; 3],
    /// The floor's material, as `object`.
    pub floor: [[f32; 4]; 3],
    /// The sphere: (centre, radius).
    pub sphere: [f32; 4],
    /// (floor height, half extent, smallest α of the point lights, 0).
    pub floor_plane: [f32; 4],
    /// The lights taken out of the environment: (entries the split-sum view shades, disc
    /// cells the truth view integrates after them, how many cast a shadow (light k has
    /// map k, 0 with shadows off), the shadow maps' edge in texels).
    pub sun: [u32; 4],
    /// The lights' shadow maps, by light (`view::shadow::ShadowMap::uniform`).
    pub shadow: [[[f32; 4]; 4]; MAX_SHADOW_MAPS],
}

/// The most lights with a shadow map: every light split out (`MAX_SHADOW_MAPS` in
/// view_frame.wgsl, whose visibilities are a vec4).
pub const MAX_SHADOW_MAPS: usize = MAX_LIGHTS;

fn pack(m: &ShadeMaterial) -> [[f32; 4]; 3] {
    [
        m.f0.extend(m.metallic).into(),
        m.albedo.extend(m.roughness).into(),
        [m.lod, m.bend, m.stretch, 0.0],
    ]
}

/// The material packed by [`FrameUniform`].
pub fn unpack_material(m: &[[f32; 4]; 3]) -> ShadeMaterial {
    ShadeMaterial {
        f0: Vec3::from_slice(&m[0][..3]),
        metallic: m[0][3],
        albedo: Vec3::from_slice(&m[1][..3]),
        roughness: m[1][3],
        lod: m[2][0],
        bend: m[2][1],
        stretch: m[2][2],
    }
}

impl FrameUniform {
    /// The block of a `width` × `height` frame seen by `camera`.
    pub fn new(
        camera: &CameraFrame,
        (width, height): (u32, u32),
        object: &ShadeMaterial,
        floor: &ShadeMaterial,
        light_count: u32,
        truth_frame: u32,
    ) -> FrameUniform {
        let vp: Mat4 = camera.view_projection();
        FrameUniform {
            width,
            height,
            truth_frame,
            light_count,
            position: camera
                .position
                .extend(if camera.orthographic { 1.0 } else { 0.0 })
                .into(),
            right: camera.right.extend(camera.half_x).into(),
            up: camera.up.extend(camera.half_y).into(),
            front: camera.front.extend(MIN_N_DOT_V).into(),
            view_projection: vp.to_cols_array_2d(),
            object: pack(object),
            floor: pack(floor),
            sphere: Vec3::from(OBJECT_CENTRE).extend(FIT_HALF_EXTENT).into(),
            floor_plane: [FLOOR_Y, FLOOR_HALF_EXTENT, MIN_DIRECT_ALPHA, 0.0],
            sun: [0; 4],
            shadow: [[[0.0; 4]; 4]; MAX_SHADOW_MAPS],
        }
    }

    /// The frame with `light`'s split-out lights on and their shadow maps: each map's
    /// block (`view::shadow::ShadowMap::uniform`), light by light (none: no shadows; at
    /// most [`MAX_SHADOW_MAPS`] are kept), and the maps' edge in texels.
    pub fn with_sun(
        mut self,
        light: &ViewLight,
        (blocks, edge): (&[[[f32; 4]; 4]], u32),
    ) -> FrameUniform {
        let maps = blocks.len().min(MAX_SHADOW_MAPS);
        self.sun = [
            light.sun_count(),
            light.sun_cell_count(),
            maps as u32,
            if maps > 0 { edge } else { 0 },
        ];
        self.shadow[..maps].copy_from_slice(&blocks[..maps]);
        self
    }

    /// The camera basis and projection back.
    pub fn camera(&self) -> CameraFrame {
        CameraFrame {
            position: Vec3::from_slice(&self.position[..3]),
            right: Vec3::from_slice(&self.right[..3]),
            up: Vec3::from_slice(&self.up[..3]),
            front: Vec3::from_slice(&self.front[..3]),
            half_x: self.right[3],
            half_y: self.up[3],
            orthographic: self.position[3] > 0.5,
        }
    }
}

/// The point lights as the kernels read them: (position, 0), (colour, 0) each.
pub fn light_table(lights: &[PointLight]) -> Vec<[f32; 4]> {
    lights
        .iter()
        .flat_map(|l| {
            [
                [l.position[0], l.position[1], l.position[2], 0.0],
                [l.colour[0], l.colour[1], l.colour[2], 0.0],
            ]
        })
        .collect()
}

/// Uniform block of the present pass (`shaders/view_present.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct PresentUniform {
    /// Frame width in pixels.
    pub width: u32,
    /// Frame height in pixels.
    pub height: u32,
    /// [`Mode`].
    pub mode: u32,
    /// Unused, 0 (keeps the block's size; whether the target stores sRGB itself is a
    /// constant of each pipeline, `TARGET_IS_SRGB` in `shaders/common/view_display.wgsl`).
    pub reserved: u32,
    /// Linear exposure scale.
    pub exposure: f32,
    /// log10 of the heat map's ends (`HEAT_LOG10_RANGE`).
    pub heat_lo: f32,
    /// See `heat_lo`.
    pub heat_hi: f32,
    /// Entries of the heat map's colour table.
    pub heat_entries: u32,
}

impl PresentUniform {
    /// The block for a frame.
    pub fn new((width, height): (u32, u32), mode: Mode, exposure: f32) -> Self {
        PresentUniform {
            width,
            height,
            mode: mode as u32,
            reserved: 0,
            exposure,
            heat_lo: HEAT_LOG10_RANGE[0],
            heat_hi: HEAT_LOG10_RANGE[1],
            heat_entries: HEAT_TABLE_ENTRIES,
        }
    }
}

/// Entries of the heat map's colour table (matplotlib's inferno, from `colorous`),
/// interpolated linearly between entries by the present pass.
pub const HEAT_TABLE_ENTRIES: u32 = 256;

/// The heat map's colour table: 8-bit sRGB inferno at t = i/(N − 1), as 0–1 floats.
pub fn heat_table() -> Vec<[f32; 4]> {
    (0..HEAT_TABLE_ENTRIES)
        .map(|i| {
            let c = colorous::INFERNO.eval_continuous(i as f64 / (HEAT_TABLE_ENTRIES - 1) as f64);
            [
                c.r as f32 / 255.0,
                c.g as f32 / 255.0,
                c.b as f32 / 255.0,
                1.0,
            ]
        })
        .collect()
}
