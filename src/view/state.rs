//! What the user controls in the viewer, the actions that change it, and the names of
//! those actions: the window's keys ([`KEYS`], the README's key table) and the tokens of
//! `--keys` (the same actions for offscreen renders and tests).

use crate::view::camera::Camera;
use crate::view::frame::Mode;
use crate::view::scene::{materials, BaseMaterial};
use crate::{Error, Result};

/// Roughness at start.
pub const START_ROUGHNESS: f32 = 0.25;
/// Roughness change per key press.
pub const ROUGHNESS_STEP: f32 = 0.05;
/// Exposure change per key press, stops.
pub const EXPOSURE_STEP_EV: f32 = 0.5;
/// Seconds of movement one `w`/`a`/`s`/`d` token stands for (a tenth of a second's walk).
pub const TOKEN_STEP_SECONDS: f32 = 0.1;

/// Everything the user sets.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewState {
    /// Index into the materials (0–5: keys 1–6).
    pub material: usize,
    /// The six materials, with their metallic flags as toggled.
    pub materials: [BaseMaterial; 6],
    /// Perceptual roughness of the object, 0–1.
    pub roughness: f32,
    /// Index into the models.
    pub model: usize,
    /// Exposure relative to the environment's default, stops.
    pub exposure_ev: f32,
    /// What is shown.
    pub mode: Mode,
    /// Whether the point lights shine.
    pub lights: bool,
    /// Whether the HUD is drawn.
    pub hud: bool,
    /// Whether the lights split out of the environment cast their shadows.
    pub shadow: bool,
    /// The camera.
    pub camera: Camera,
}

impl Default for ViewState {
    fn default() -> Self {
        ViewState {
            material: 0,
            materials: materials(),
            roughness: START_ROUGHNESS,
            model: 0,
            exposure_ev: 0.0,
            mode: Mode::SplitSum,
            lights: false,
            hud: true,
            shadow: true,
            camera: Camera::default(),
        }
    }
}

/// A change the user asks for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Action {
    /// Material 0–5.
    Material(usize),
    /// Model by index.
    Model(usize),
    /// The next model.
    NextModel,
    /// The previous model.
    PreviousModel,
    /// Roughness up one step.
    RougherBy,
    /// Roughness down one step.
    SmootherBy,
    /// The current material's metallic flag flipped.
    ToggleMetallic,
    /// Exposure up one step.
    Brighter,
    /// Exposure down one step.
    Darker,
    /// Ground truth on or off.
    ToggleTruth,
    /// Heat map on or off.
    ToggleHeat,
    /// Point lights on or off.
    ToggleLights,
    /// HUD on or off.
    ToggleHud,
    /// The sun split out of the environment (a light with a shadow) or kept in it; the
    /// viewer swaps its light (the state holds nothing of it).
    ToggleSun,
    /// The lights' shadows on or off.
    ToggleShadow,
    /// A walk of `forward`, `sideways` for a tenth of a second (the `w a s d` tokens).
    Walk(f32, f32),
    /// Save a screenshot.
    Screenshot,
    /// Quit.
    Quit,
}

/// The window's keys: (key as the README names it, `--keys` token, what it does, the
/// HUD's short form).
pub const KEYS: &[(&str, &str, &str, &str)] = &[
    (
        "1–6",
        "1 … 6",
        "material: gold, copper, aluminium, titanium, silver, dielectric",
        "1–6 material",
    ),
    (
        "7 8 9 0",
        "m1 … m4",
        "model: Spot, sphere, torus, the --model file",
        "7 8 9 0 model",
    ),
    (
        "Tab / Shift+Tab",
        "m+ / m-",
        "next / previous model",
        "Tab next model",
    ),
    (
        "R / F",
        "r+ / r-",
        "roughness up / down by 0.05",
        "R/F roughness",
    ),
    (
        "T",
        "t",
        "metallic on / off for this material",
        "T metallic",
    ),
    (
        "+ / −",
        "e+ / e-",
        "exposure up / down by ½ stop",
        "+/− exposure",
    ),
    (
        "G",
        "g",
        "ground truth on / off (accumulates while the view is still)",
        "G truth",
    ),
    (
        "H",
        "h",
        "heat map |split-sum − truth| / truth on / off",
        "H heat map",
    ),
    ("L", "l", "point lights on / off", "L lights"),
    (
        "U",
        "u",
        "the sun split out as a light or kept in the IBL (an HDRI with a sun)",
        "U sun split/kept",
    ),
    ("O", "o", "the lights' shadows on / off", "O shadow"),
    ("F1", "hud", "HUD on / off", "F1 HUD"),
    (
        "W A S D, mouse",
        "w a s d",
        "move; look while the cursor is captured",
        "WASD move",
    ),
    (
        "C / V",
        "",
        "capture / release the cursor",
        "C/V mouse look",
    ),
    ("P", "", "screenshot to splitsum-view-N.png", "P screenshot"),
    ("Esc", "", "quit", "Esc quit"),
];

/// The actions of a `--keys` string: tokens separated by spaces or commas.
pub fn parse_keys(keys: &str) -> Result<Vec<Action>> {
    keys.split([' ', ','])
        .filter(|t| !t.is_empty())
        .map(|t| {
            let action = match t {
                "r+" => Action::RougherBy,
                "r-" => Action::SmootherBy,
                "m+" => Action::NextModel,
                "m-" => Action::PreviousModel,
                "t" => Action::ToggleMetallic,
                "e+" => Action::Brighter,
                "e-" => Action::Darker,
                "g" => Action::ToggleTruth,
                "h" => Action::ToggleHeat,
                "l" => Action::ToggleLights,
                "u" => Action::ToggleSun,
                "o" => Action::ToggleShadow,
                "hud" => Action::ToggleHud,
                "w" => Action::Walk(1.0, 0.0),
                "s" => Action::Walk(-1.0, 0.0),
                "a" => Action::Walk(0.0, -1.0),
                "d" => Action::Walk(0.0, 1.0),
                _ => match (t.strip_prefix('m'), t.parse::<usize>()) {
                    (_, Ok(n @ 1..=6)) => Action::Material(n - 1),
                    (Some(m), _) if matches!(m.parse::<usize>(), Ok(1..=9)) => {
                        Action::Model(m.parse::<usize>().unwrap_or(1) - 1)
                    }
                    _ => {
                        return Err(Error::InvalidOption {
                            option: "keys",
                            message: format!(
                                "'{t}' is not a key token (1…6, m1…m4, m+, m-, r+, r-, t, e+, e-, g, h, l, u, o, hud, w, a, s, d)"
                            ),
                        })
                    }
                },
            };
            Ok(action)
        })
        .collect()
}

/// What an action changed, for the caller to act on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Change {
    /// Nothing (a model key with no model behind it).
    Nothing,
    /// What is seen (material, model, camera, lights): the truth restarts.
    Scene,
    /// Only how it is shown (exposure, mode, HUD): the truth goes on.
    Display,
    /// A screenshot is wanted.
    Screenshot,
    /// The user quits.
    Quit,
}

impl ViewState {
    /// The current material.
    pub fn base_material(&self) -> &BaseMaterial {
        &self.materials[self.material]
    }

    /// Applies `action` with `models` models loaded.
    pub fn apply(&mut self, action: Action, models: usize) -> Change {
        let toggle = |mode: &mut Mode, m: Mode| {
            *mode = if *mode == m { Mode::SplitSum } else { m };
        };
        match action {
            Action::Material(m) => self.material = m.min(5),
            Action::Model(m) if m < models => self.model = m,
            Action::Model(_) => return Change::Nothing,
            Action::NextModel => self.model = (self.model + 1) % models.max(1),
            Action::PreviousModel => self.model = (self.model + models.max(1) - 1) % models.max(1),
            Action::RougherBy => self.roughness = step(self.roughness, ROUGHNESS_STEP),
            Action::SmootherBy => self.roughness = step(self.roughness, -ROUGHNESS_STEP),
            Action::ToggleMetallic => {
                let m = &mut self.materials[self.material];
                m.metallic = !m.metallic;
            }
            Action::ToggleLights => self.lights = !self.lights,
            Action::ToggleShadow => self.shadow = !self.shadow,
            Action::ToggleSun => {}
            Action::Walk(f, s) => self.camera.walk(f, s, TOKEN_STEP_SECONDS),
            Action::Brighter => {
                self.exposure_ev += EXPOSURE_STEP_EV;
                return Change::Display;
            }
            Action::Darker => {
                self.exposure_ev -= EXPOSURE_STEP_EV;
                return Change::Display;
            }
            Action::ToggleTruth => {
                toggle(&mut self.mode, Mode::Truth);
                return Change::Display;
            }
            Action::ToggleHeat => {
                toggle(&mut self.mode, Mode::Heat);
                return Change::Display;
            }
            Action::ToggleHud => {
                self.hud = !self.hud;
                return Change::Display;
            }
            Action::Screenshot => return Change::Screenshot,
            Action::Quit => return Change::Quit,
        }
        Change::Scene
    }
}

/// `r + delta` on the grid of [`ROUGHNESS_STEP`]s, within [0, 1] (so that steps add up to
/// exact grid values, not accumulated rounding).
fn step(r: f32, delta: f32) -> f32 {
    let k = ((r + delta) / ROUGHNESS_STEP).round();
    (k * ROUGHNESS_STEP).clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The `--keys` example: copper, two steps rougher, the sphere, the ground truth.
    #[test]
    fn keys_parse_and_apply() {
        let actions = parse_keys("2 r+ r+ m2 g").unwrap();
        let mut s = ViewState::default();
        for a in actions {
            s.apply(a, 3);
        }
        assert_eq!(s.base_material().name, "copper");
        assert!((s.roughness - 0.35).abs() < 1e-6);
        assert_eq!((s.model, s.mode), (1, Mode::Truth));
        assert!(parse_keys("2 x").unwrap_err().to_string().contains("'x'"));
        assert_eq!(s.apply(Action::Model(7), 3), Change::Nothing);
    }

    /// Roughness stays on its grid and within [0, 1].
    #[test]
    fn roughness_steps() {
        let mut s = ViewState::default();
        for _ in 0..40 {
            s.apply(Action::RougherBy, 3);
        }
        assert_eq!(s.roughness, 1.0);
        for _ in 0..40 {
            s.apply(Action::SmootherBy, 3);
        }
        assert_eq!(s.roughness, 0.0);
    }
}
