//! splitsum's helper for Bevy 0.19, to copy next to your code (`mod splitsum_bevy;`) as
//! `js/splitsum-three.js` is for three.js: [`CompensatedRectLights`] shades Bevy's
//! `RectLight` as splitsum's preview shades an area light (docs/targets.md, "Area lights").
//!
//! Bevy 0.19's `rect_light` (bevy_pbr's `pbr_lighting.wgsl`, feature `area_light_luts`)
//! shades the specular from Heitz's LTC table alone, whose fit is 8–10 % off the GGX lobe at
//! r ≥ 0.35, and leaves out the multiple-scattering compensation 1 + F0 (1 / (A + B) − 1)
//! that its punctual and directional lights apply (`specular_multiscatter`): a white metal
//! sphere under a studio's lamps is tens of per cent too dark. The plugin patches that
//! function's return: the LTC becomes a control variate, LTC + β (the exact BRDF at the
//! rectangle's centre − the LTC's density there) Ω with β = 4πα² / (4πα² + Ω) (Bevy's own
//! GGX, height-correlated visibility and Fresnel there, through its `specular`), and the
//! LTC's terms get the compensation that `specular` applies. The diffuse stays Bevy's
//! (Lambert's form factor).

use bevy::prelude::*;
use bevy::shader::{Shader, Source};

/// Patches Bevy 0.19's rect-light shading (see the module's doc). Panics where the shader
/// is not 0.19's (the line it replaces is not there): without the patch the lights render
/// uncompensated.
pub struct CompensatedRectLights;

/// Where bevy_pbr embeds the shader the patch rewrites.
const LIGHTING_SHADER: &str = "embedded://bevy_pbr/render/pbr_lighting.wgsl";

/// The line of bevy_pbr 0.19's `rect_light` (without clearcoat) that the patch replaces.
const RECT_RETURN: &str =
    "    return (spec_weight * spec + diffuse_color * diff) * (*light).color.rgb * range_falloff;";

/// What takes its place.
const RECT_COMPENSATED: &str = "    // splitsum (splitsum_bevy.rs, CompensatedRectLights): the LTC as a control variate
    // at the rectangle's centre with Bevy's own BRDF there, and the multiple-scattering
    // compensation of specular_multiscatter on the LTC's terms.
    let splitsum_c = normalize((*light).position - P);
    // The rectangle's solid angle from P: two spherical triangles (Van Oosterom and
    // Strackee 1983).
    var splitsum_p: array<vec3<f32>, 4>;
    for (var i = 0; i < 4; i++) {
        splitsum_p[i] = normalize(corners[i] - P);
    }
    var splitsum_omega = 0.0;
    for (var i = 1; i < 3; i++) {
        let a = splitsum_p[0];
        let b = splitsum_p[i];
        let c = splitsum_p[i + 1];
        splitsum_omega += 2.0 * atan2(abs(dot(a, cross(b, c))), 1.0 + dot(a, b) + dot(b, c) + dot(c, a));
    }
    // The LTC's density at the centre: D_o(M^-1 c / |M^-1 c|) |det M^-1| / |M^-1 c|^3, in
    // ltc_integrate_quad's frame.
    let splitsum_t1 = normalize(V - N * dot(V, N));
    let splitsum_t2 = -cross(N, splitsum_t1);
    let splitsum_lo = Minv * (transpose(mat3x3<f32>(splitsum_t1, splitsum_t2, N)) * splitsum_c);
    let splitsum_len = length(splitsum_lo);
    let splitsum_density = max(splitsum_lo.z / splitsum_len, 0.0) / PI * abs(determinant(Minv))
        / (splitsum_len * splitsum_len * splitsum_len);
    let splitsum_alpha = (*input).layers[LAYER_BASE].roughness;
    let splitsum_lobe = 4.0 * PI * splitsum_alpha * splitsum_alpha;
    let splitsum_beta = splitsum_lobe / (splitsum_lobe + splitsum_omega);
    var splitsum_derived = derive_lighting_input(N, V, splitsum_c);
    // specular() applies the compensation itself.
    let splitsum_point = specular(input, &splitsum_derived, splitsum_alpha, 1.0) * splitsum_derived.NdotL * splitsum_omega;
    let splitsum_ab = (*input).F_ab;
    let splitsum_compensation = 1.0 + F0 * (1.0 / (splitsum_ab.x + splitsum_ab.y) - 1.0);
    let splitsum_ltc = spec_weight * (spec - splitsum_beta * splitsum_density * splitsum_omega) * splitsum_compensation;
    let splitsum_specular = max(splitsum_ltc + splitsum_beta * splitsum_point, vec3<f32>(0.0));
    return (splitsum_specular + diffuse_color * diff) * (*light).color.rgb * range_falloff;";

impl Plugin for CompensatedRectLights {
    fn build(&self, app: &mut App) {
        app.add_systems(Update, patch_rect_lights);
    }
}

/// Rewrites the lighting shader once it is loaded; Bevy then recompiles what uses it.
fn patch_rect_lights(
    assets: Res<AssetServer>,
    mut shaders: ResMut<Assets<Shader>>,
    mut handle: Local<Option<Handle<Shader>>>,
    mut done: Local<bool>,
) {
    if *done {
        return;
    }
    let handle = handle.get_or_insert_with(|| assets.load(LIGHTING_SHADER));
    let Some(mut shader) = shaders.get_mut(handle.id()) else {
        return;
    };
    let Source::Wgsl(source) = &mut shader.source else {
        panic!("CompensatedRectLights: {LIGHTING_SHADER} is not WGSL");
    };
    assert!(
        source.contains(RECT_RETURN),
        "CompensatedRectLights: {LIGHTING_SHADER} is not Bevy 0.19's (its rect_light has no line '{}')",
        RECT_RETURN.trim()
    );
    *source = source.replace(RECT_RETURN, RECT_COMPENSATED).into();
    *done = true;
}
