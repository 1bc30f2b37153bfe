// Inverse trigonometry accurate to a few ULP and identical on every driver (Vulkan
// allows 4096 ULP for atan/acos). Mirror of src/math/trig.rs (same function names).

const PI: f32 = 3.14159265358979323846;
const FRAC_PI_2: f32 = 1.57079632679489661923;

// atan minimax coefficients (Cephes atanf); equal to ATAN_COEFFS in src/math/trig.rs
// (checked by tests/shaders.rs).
const ATAN_C0: f32 = -3.333295e-1;
const ATAN_C1: f32 = 1.9977711e-1;
const ATAN_C2: f32 = -1.3877686e-1;
const ATAN_C3: f32 = 8.0537445e-2;

// atan to a few ULP, identical on every driver (Vulkan allows 4096 ULP for atan).
fn atan_precise(x: f32) -> f32 {
    let a = abs(x);
    var base = 0.0;
    var t = a;
    if (a > 2.4142136) {
        base = 0.5 * PI;
        t = -1.0 / a;
    } else if (a > 0.41421357) {
        base = 0.25 * PI;
        t = (a - 1.0) / (a + 1.0);
    }
    let z = t * t;
    let r = base + t + t * z * (ATAN_C0 + z * (ATAN_C1 + z * (ATAN_C2 + z * ATAN_C3)));
    return select(r, -r, x < 0.0);
}

fn atan2_precise(y: f32, x: f32) -> f32 {
    if (x > 0.0) {
        return atan_precise(y / x);
    } else if (x < 0.0) {
        let a = atan_precise(y / x);
        return select(a - PI, a + PI, y >= 0.0);
    } else if (y > 0.0) {
        return 0.5 * PI;
    } else if (y < 0.0) {
        return -0.5 * PI;
    }
    return 0.0;
}

// acos(x) = atan2(sqrt(1 - x^2), x).
fn acos_precise(x_in: f32) -> f32 {
    let x = clamp(x_in, -1.0, 1.0);
    return atan2_precise(sqrt(max(1.0 - x * x, 0.0)), x);
}
