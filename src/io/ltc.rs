//! Writes and reads an LTC table ([`crate::plan::ltc::LtcTable`]) as JSON in the layout
//! three.js's `RectAreaLightTexturesLib` builds its textures from: `ltc_1` and `ltc_2`,
//! `size`² RGBA texels each, row-major from row 0 (n·v = 1) and column 0 (r = 0), read at
//! uv = (r, √(1 − n·v)) scaled into the texel centres. `ltc_1` holds M⁻¹ / M⁻¹₁₁ as
//! (M⁻¹₀₀, M⁻¹₂₀, M⁻¹₀₂, M⁻¹₂₂) (row, column), which `mat3(vec3(x, 0, y), vec3(0, 1, 0),
//! vec3(z, 0, w))` takes by columns; `ltc_2` holds (A + B, B, 0, 0): the lobe's magnitude
//! with F = 1 and its Fresnel part, which a shader scales by F0 A + F90 B. A page uploads
//! them as 32-bit float `DataTexture`s (bilinear, clamped) in place of three's own.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::atomic::write_atomic;
use crate::plan::ltc::{LtcCell, LtcTable};
use crate::plan::shading::{DiffuseLobe, LightBrdf, Masking};
use crate::{Error, Result};

/// What the file's numbers mean.
const ABOUT: &str = "LTC table (Heitz, Dupuy, Hill, Neubelt 2016) of the GGX lobe with the masking named, in three.js RectAreaLightTexturesLib's layout: ltc_1 and ltc_2 are size x size RGBA texels, row-major, row j at sqrt(1 - n.v) = j / (size - 1), column i at roughness r = i / (size - 1) (alpha = r^2, at least 1e-3); sample at uv = (r, sqrt(1 - n.v)) * (size - 1) / size + 0.5 / size. ltc_1: M^-1 / M^-1[1][1] as (m00, m20, m02, m22) (row, column), the columns of mat3(vec3(x, 0, y), vec3(0, 1, 0), vec3(z, 0, w)); ltc_2: (A + B, B, 0, 0), the lobe's integral with F = 1 and its Fresnel part (scale by F0 A + F90 B)";

/// The file.
#[derive(Serialize, Deserialize)]
struct LtcJson {
    about: String,
    /// The specular masking fitted: `smith-correlated` or `schlick-ggx`.
    masking: String,
    size: u32,
    ltc_1: Vec<f32>,
    ltc_2: Vec<f32>,
}

/// The name of a masking in the file.
fn masking_name(m: Masking) -> &'static str {
    match m {
        Masking::SmithCorrelated => "smith-correlated",
        Masking::SchlickGgx => "schlick-ggx",
    }
}

/// `table` as the file's text.
pub fn encode_ltc(table: &LtcTable) -> String {
    let json = LtcJson {
        about: ABOUT.into(),
        masking: masking_name(table.brdf.masking).into(),
        size: table.size,
        ltc_1: table.cells.iter().flat_map(|c| c.inverse).collect(),
        ltc_2: table
            .cells
            .iter()
            .flat_map(|c| [c.norm, c.fresnel, 0.0, 0.0])
            .collect(),
    };
    // Compact: 2 × 4 size² numbers.
    let mut text = serde_json::to_string(&json).unwrap_or_default();
    text.push('\n');
    text
}

/// Writes `table` to `path` (`.json`) atomically.
pub fn write_ltc(path: &Path, table: &LtcTable) -> Result<()> {
    super::check_output_extension(path, "an LTC table", &["json"])?;
    write_atomic(path, encode_ltc(table).as_bytes())
}

/// Reads a table [`write_ltc`] wrote. Its BRDF's diffuse lobe (which the fit does not
/// read) is Fresnel-weighted and uncompensated.
pub fn read_ltc(path: &Path) -> Result<LtcTable> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    let bad = |message: String| Error::Decode {
        path: path.to_path_buf(),
        format: "JSON",
        message,
    };
    let j: LtcJson = serde_json::from_str(&text)
        .map_err(|e| bad(format!("{e} (not an LTC table splitsum wrote?)")))?;
    let masking = [Masking::SmithCorrelated, Masking::SchlickGgx]
        .into_iter()
        .find(|&m| masking_name(m) == j.masking)
        .ok_or_else(|| bad(format!("unknown masking '{}'", j.masking)))?;
    let cells = (j.size as usize).pow(2);
    if j.size < 2 || j.ltc_1.len() != 4 * cells || j.ltc_2.len() != 4 * cells {
        return Err(bad(format!(
            "size {} wants 2 × {} numbers, found {} and {}",
            j.size,
            4 * cells,
            j.ltc_1.len(),
            j.ltc_2.len()
        )));
    }
    Ok(LtcTable {
        size: j.size,
        brdf: LightBrdf {
            masking,
            diffuse: DiffuseLobe::FresnelWeighted,
            compensated: false,
        },
        cells: (0..cells)
            .map(|k| LtcCell {
                inverse: std::array::from_fn(|c| j.ltc_1[4 * k + c]),
                norm: j.ltc_2[4 * k],
                fresnel: j.ltc_2[4 * k + 1],
            })
            .collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip() {
        let table = LtcTable::fit(LightBrdf::GENERIC, 4);
        let dir = std::env::temp_dir().join(format!("splitsum-ltc-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("ltc.json");
        write_ltc(&path, &table).unwrap();
        let back = read_ltc(&path).unwrap();
        assert_eq!(back, table);
        assert!(write_ltc(&dir.join("ltc.png"), &table).is_err());
        std::fs::write(&path, "{\"size\": 2}").unwrap();
        assert!(matches!(read_ltc(&path), Err(Error::Decode { .. })));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
