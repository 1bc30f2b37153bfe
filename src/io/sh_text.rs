//! cmgen's text forms of Filament's SH (Filament `tools/cmgen`, `--sh-shader`): the `sh`
//! value of an `*_ibl.ktx` (nine "r g b" lines, which Filament's `Ktx1Bundle::
//! getSphericalHarmonics` and its web build's `createIblFromKtx1` parse with strtof), and
//! `sh.txt` (nine "(r, g, b); // L00, irradiance, pre-scaled base" lines, for tools and
//! C++ code that paste them into `IndirectLight::Builder::irradiance(3, sh)`).
//!
//! Both hold [`crate::math::sh::sh_prescaled`] coefficients: Filament's shader evaluates
//! them as `sh[0] + sh[1]·y + sh[2]·z + sh[3]·x + sh[4]·yx + sh[5]·yz + sh[6]·(3z² − 1) +
//! sh[7]·zx + sh[8]·(x² − y²)` (`Irradiance_SphericalHarmonics`) and takes the result as
//! E/π.

/// cmgen's names of the coefficients, in order.
const NAMES: [&str; 9] = [
    "L00", "L1-1", "L10", "L11", "L2-2", "L2-1", "L20", "L21", "L22",
];

/// The `sh` key/value text of an `*_ibl.ktx`: one "r g b" line per coefficient, with the
/// NUL the KTX specification recommends after a text value. Shortest round-trip decimals,
/// so a reader gets the f32 values back exactly.
pub fn ktx_value(prescaled: &[[f32; 3]; 9]) -> Vec<u8> {
    let mut s = String::new();
    for c in prescaled {
        s.push_str(&format!("{} {} {}\n", c[0], c[1], c[2]));
    }
    let mut bytes = s.into_bytes();
    bytes.push(0);
    bytes
}

/// `sh.txt` as cmgen writes it.
pub fn sh_txt(prescaled: &[[f32; 3]; 9]) -> String {
    let mut s = String::new();
    for (c, name) in prescaled.iter().zip(NAMES) {
        s.push_str(&format!(
            "({:>18.15}, {:>18.15}, {:>18.15}); // {name}, irradiance, pre-scaled base\n",
            c[0], c[1], c[2]
        ));
    }
    s
}

#[cfg(any(test, feature = "internals"))]
/// Parses nine "r g b" triples (either form: separators are whitespace, commas,
/// parentheses and semicolons; `//` comments are skipped), as Filament's readers do.
pub fn parse(text: &str) -> Option<[[f32; 3]; 9]> {
    let mut values = Vec::with_capacity(27);
    for line in text.lines() {
        let line = line.split("//").next().unwrap_or("");
        for token in line.split(|c: char| c.is_whitespace() || "(),;\0".contains(c)) {
            if !token.is_empty() {
                values.push(token.parse::<f32>().ok()?);
            }
        }
    }
    (values.len() == 27)
        .then(|| std::array::from_fn(|i| [values[3 * i], values[3 * i + 1], values[3 * i + 2]]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_forms_read_back_exactly() {
        let c: [[f32; 3]; 9] =
            std::array::from_fn(|i| [0.1 * i as f32, -0.3333333 * i as f32, 1e-7 + i as f32]);
        let ktx = ktx_value(&c);
        assert_eq!(ktx.last(), Some(&0));
        assert_eq!(parse(std::str::from_utf8(&ktx).unwrap()), Some(c));
        let txt = sh_txt(&c);
        assert!(txt
            .lines()
            .next()
            .unwrap()
            .ends_with("// L00, irradiance, pre-scaled base"));
        let back = parse(&txt).unwrap();
        for i in 0..9 {
            for ch in 0..3 {
                assert!((back[i][ch] - c[i][ch]).abs() <= 1e-14_f32.max(c[i][ch].abs() * 1e-6));
            }
        }
        assert_eq!(parse("1 2 3"), None);
    }
}
