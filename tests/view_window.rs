//! `splitsum view` in a real window: under Xvfb (a virtual X server) on the GPU adapter
//! (lavapipe in CI), keys sent with xdotool through XTEST as a keyboard would, the window
//! captured with xwd and converted by ImageMagick. Needs `Xvfb`, `xdotool`, `xwd` and
//! `convert` (`.ci/run` installs them); without them the test says so and passes, unless
//! `SPLITSUM_REQUIRE_WINDOW=1` (set by `.ci/run`), where it fails.
//!
//! Checked: the window opens and shows the bundled HDRI baked (its title names it); after
//! the keys 2 (copper), R (rougher), 8 (the sphere), G (ground truth) the HUD's material
//! line and the object are what the same keys give offscreen (`--keys "2 r+ m2 g"`), and
//! differ from before the keys; a 1 × 1 window, an unmapped and remapped one do not stop
//! it; Escape ends it with exit code 0. On quarry_01 (a sun, split out at start), the keys
//! O and U change the HUD's sun line as `--keys "o"` and `--keys "o u"` do offscreen, and
//! a key held down while the window gains focus is not a press. Each check waits on the
//! window's picture (captured until it shows what is expected), never on a timer.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use common::{output_dir, run_ok, splitsum};
use image::RgbImage;

const SIZE: (u32, u32) = (640, 360);

fn have(tool: &str) -> bool {
    Command::new("sh")
        .args(["-c", &format!("command -v {tool}")])
        .stdout(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// Kills a child process when dropped (Xvfb, or the viewer if the test fails).
struct Reaped(Child);

impl Drop for Reaped {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// A free display number and Xvfb on it, answering requests. `-noreset`: without it the
/// server resets each time its last client leaves (every `xdotool` call before the viewer
/// connects), and a client that connects during a reset is dropped.
fn start_xvfb(log: &Path) -> (String, Reaped) {
    let n = (90..140)
        .find(|n| {
            !Path::new(&format!("/tmp/.X11-unix/X{n}")).exists()
                && !Path::new(&format!("/tmp/.X{n}-lock")).exists()
        })
        .expect("a free X display number");
    let display = format!(":{n}");
    let child = Command::new("Xvfb")
        .args([
            &display,
            "-screen",
            "0",
            "1024x768x24",
            "-nolisten",
            "tcp",
            "-noreset",
        ])
        .stdout(Stdio::null())
        .stderr(std::fs::File::create(log).unwrap())
        .spawn()
        .expect("Xvfb starts");
    let started = Instant::now();
    // The socket appears before the server has set up its screen and keyboard: wait until
    // it answers a request.
    while xdotool(&display, &["getdisplaygeometry"]).is_empty() {
        assert!(
            started.elapsed() < Duration::from_secs(20),
            "Xvfb did not start: {}",
            std::fs::read_to_string(log).unwrap_or_default()
        );
        std::thread::sleep(Duration::from_millis(100));
    }
    (display, Reaped(child))
}

fn xdotool(display: &str, args: &[&str]) -> String {
    let out = Command::new("xdotool")
        .args(args)
        .env("DISPLAY", display)
        .output()
        .unwrap();
    String::from_utf8_lossy(&out.stdout).trim().to_string()
}

/// What a finished child wrote to its (piped) standard error.
fn stderr_of(child: &mut Child) -> String {
    use std::io::Read;
    let mut stderr = String::new();
    if let Some(mut e) = child.stderr.take() {
        let _ = e.read_to_string(&mut stderr);
    }
    stderr
}

/// The window whose title contains `title`, waiting up to `seconds`; Err with the
/// viewer's exit status and stderr if it exits first.
fn wait_for_window(
    display: &str,
    title: &str,
    viewer: &mut Child,
    seconds: u64,
) -> Result<String, String> {
    let started = Instant::now();
    loop {
        let ids = xdotool(display, &["search", "--name", title]);
        if let Some(id) = ids.lines().next() {
            return Ok(id.to_string());
        }
        if let Ok(Some(status)) = viewer.try_wait() {
            return Err(format!(
                "the viewer exited before showing '{title}': {status}: {}",
                stderr_of(viewer)
            ));
        }
        assert!(
            started.elapsed() < Duration::from_secs(seconds),
            "no window titled '{title}'"
        );
        std::thread::sleep(Duration::from_millis(250));
    }
}

/// The window's picture (xwd, converted to PNG by ImageMagick).
fn capture(display: &str, window: &str, path: &Path) -> RgbImage {
    let status = Command::new("sh")
        .args([
            "-c",
            &format!(
                "xwd -silent -id {window} | convert xwd:- png:'{}'",
                path.display()
            ),
        ])
        .env("DISPLAY", display)
        .status()
        .unwrap();
    assert!(status.success(), "xwd | convert failed");
    image::open(path).unwrap().to_rgb8()
}

/// The same view offscreen, with `keys` (`input` before them: an HDRI, or nothing for
/// the bundled one).
fn offscreen(dir: &Path, name: &str, input: &[&str], keys: &str, frames: u32) -> RgbImage {
    let path: PathBuf = dir.join(name);
    run_ok(
        splitsum()
            .arg("view")
            .args(input)
            .args(["--size", &format!("{}x{}", SIZE.0, SIZE.1), "--keys", keys])
            .args(["--frames", &frames.to_string(), "--screenshot"])
            .arg(&path),
    );
    image::open(&path).unwrap().to_rgb8()
}

/// The window tools are here (without them the test passes saying so, unless
/// `SPLITSUM_REQUIRE_WINDOW=1`): this test's turn at starting an X server, held until
/// it ends.
fn window_turn() -> Option<std::sync::MutexGuard<'static, ()>> {
    let required = std::env::var("SPLITSUM_REQUIRE_WINDOW").is_ok_and(|v| v == "1");
    let missing: Vec<&str> = ["Xvfb", "xdotool", "xwd", "convert"]
        .into_iter()
        .filter(|t| !have(t))
        .collect();
    if !missing.is_empty() {
        assert!(
            !required,
            "SPLITSUM_REQUIRE_WINDOW=1 but {missing:?} missing"
        );
        eprintln!("skipping the window test: {missing:?} not installed");
        return None;
    }
    Some(
        ONE_SERVER_AT_A_TIME
            .lock()
            .unwrap_or_else(|e| e.into_inner()),
    )
}

/// A viewer window of `input` (nothing: the bundled HDRI) on a new X server, once its
/// title names `title` (the bake is shown): (display, the server, the viewer, the
/// window). A start the X server refuses (the display unreachable, no window granted) is
/// the server's doing, not the viewer's, and is tried again on a new server, at most
/// twice; any other early exit fails the test.
fn open_window(dir: &Path, input: &[&str], title: &str) -> (String, Reaped, Reaped, String) {
    let mut attempts = 0;
    loop {
        attempts += 1;
        let (display, xvfb) = start_xvfb(&dir.join(format!("xvfb_{attempts}.log")));
        let mut viewer = Reaped(
            splitsum()
                .arg("view")
                .args(input)
                .args(["--size", &format!("{}x{}", SIZE.0, SIZE.1)])
                .env("DISPLAY", &display)
                .stdout(Stdio::null())
                .stderr(Stdio::piped())
                .spawn()
                .unwrap(),
        );
        match wait_for_window(&display, title, &mut viewer.0, 300) {
            Ok(window) => return (display, xvfb, viewer, window),
            Err(message) => {
                let refused_by_the_server = message.contains("cannot reach the display")
                    || message.contains("cannot open a window");
                assert!(refused_by_the_server && attempts < 3, "{message}");
                eprintln!("trying again on a new X server: {message}");
            }
        }
    }
}

/// Escape ends the viewer with exit code 0.
fn escape_ends(display: &str, window: &str, viewer: &mut Reaped) {
    xdotool(display, &["windowfocus", "--sync", window]);
    xdotool(display, &["key", "Escape"]);
    let started = Instant::now();
    let status = loop {
        if let Some(s) = viewer.0.try_wait().unwrap() {
            break s;
        }
        assert!(
            started.elapsed() < Duration::from_secs(30),
            "Escape did not end the viewer"
        );
        std::thread::sleep(Duration::from_millis(100));
    };
    assert!(
        status.success(),
        "exit {status}: {}",
        stderr_of(&mut viewer.0)
    );
}

/// The window tests take turns: each starts an X server on the first free display number,
/// and two starting at once could pick the same one.
static ONE_SERVER_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// How many pixels of a box differ by more than [`GLYPH_STEPS`] in a channel: the edges
/// of the glyphs where two lines of text differ (the same text drawn by the window and
/// offscreen differs by a few steps of rounding at most).
fn glyph_differences(a: &RgbImage, b: &RgbImage, (x, y, w, h): (u32, u32, u32, u32)) -> usize {
    let mut n = 0;
    for yy in y..y + h {
        for xx in x..x + w {
            let (p, q) = (a.get_pixel(xx, yy).0, b.get_pixel(xx, yy).0);
            if (0..3).any(|c| p[c].abs_diff(q[c]) > GLYPH_STEPS) {
                n += 1;
            }
        }
    }
    n
}

/// A difference no rounding makes: a glyph's edge against the HUD's background.
const GLYPH_STEPS: u8 = 40;

/// Mean absolute difference per channel over a box, 8-bit steps.
fn box_difference(a: &RgbImage, b: &RgbImage, (x, y, w, h): (u32, u32, u32, u32)) -> f64 {
    let mut sum = 0.0;
    for yy in y..y + h {
        for xx in x..x + w {
            let (p, q) = (a.get_pixel(xx, yy).0, b.get_pixel(xx, yy).0);
            sum += (0..3).map(|c| p[c].abs_diff(q[c]) as f64).sum::<f64>();
        }
    }
    sum / (3 * w * h) as f64
}

/// Captures the window until `done` holds for a shot (or `seconds` pass); the last shot.
fn capture_until(
    display: &str,
    window: &str,
    path: &Path,
    seconds: u64,
    done: impl Fn(&RgbImage) -> bool,
) -> RgbImage {
    let started = Instant::now();
    loop {
        let shot = capture(display, window, path);
        if done(&shot) || started.elapsed() > Duration::from_secs(seconds) {
            return shot;
        }
    }
}

#[test]
fn keys_change_the_window() {
    let Some(_turn) = window_turn() else {
        return;
    };
    let dir = output_dir("view_window");
    // The title names the HDRI once its bake is shown.
    let (display, _xvfb, mut viewer, window) = open_window(&dir, &[], "venice_sunset");
    let expected_before = offscreen(&dir, "expected_before.png", &[], "", 1);
    let expected_after = offscreen(&dir, "expected_after.png", &[], "2 r+ m2 g", 4);
    let material_line = splitsum::view::hud::line_box(1, SIZE.0);
    // The object at the frame's centre: the copper sphere after the keys (its truth is
    // noisy and converges over frames, so the mean over a box, within a few steps), not
    // Spot.
    let centre = (SIZE.0 / 2 - 20, SIZE.1 / 2 - 20, 40, 40);
    // The HUD's material line as offscreen (a few steps of rounding between the two
    // present passes), waiting until the window shows it.
    let line_matches =
        |shot: &RgbImage, expected: &RgbImage| box_difference(shot, expected, material_line) < 1.0;
    let before = capture_until(&display, &window, &dir.join("before.png"), 60, |s| {
        line_matches(s, &expected_before)
    });
    assert_eq!(before.dimensions(), SIZE);

    xdotool(&display, &["windowfocus", "--sync", &window]);
    xdotool(&display, &["key", "--delay", "100", "2", "r", "8", "g"]);
    let after = capture_until(&display, &window, &dir.join("after.png"), 60, |s| {
        line_matches(s, &expected_after) && box_difference(s, &expected_after, centre) < 4.0
    });

    let line_after = box_difference(&after, &expected_after, material_line);
    let line_before = box_difference(&before, &expected_before, material_line);
    let line_changed = box_difference(&before, &after, material_line);
    let object_after = box_difference(&after, &expected_after, centre);
    let object_changed = box_difference(&before, &after, centre);
    println!(
        "material line: {line_before:.2} / {line_after:.2} from offscreen, {line_changed:.2} changed; object {object_after:.2} from offscreen, {object_changed:.2} changed"
    );
    assert!(
        line_after < 1.0 && line_before < 1.0,
        "material line differs from offscreen: {line_after:.2}, {line_before:.2}"
    );
    assert!(
        line_changed > 3.0,
        "the material line did not change: {line_changed:.2}"
    );
    assert!(
        object_after < 4.0,
        "the sphere differs from offscreen: {object_after:.2}"
    );
    assert!(
        object_changed > 8.0,
        "the object did not change: {object_changed:.2}"
    );

    // A tiny, an unmapped and a remapped window do not stop the view: it draws the same
    // material line again once the window is back at its size.
    let size = [SIZE.0.to_string(), SIZE.1.to_string()];
    xdotool(&display, &["windowsize", "--sync", &window, "1", "1"]);
    xdotool(&display, &["windowunmap", "--sync", &window]);
    xdotool(&display, &["windowmap", "--sync", &window]);
    xdotool(
        &display,
        &["windowsize", "--sync", &window, &size[0], &size[1]],
    );
    let drawn_again = |s: &RgbImage| s.dimensions() == SIZE && line_matches(s, &expected_after);
    let back = capture_until(&display, &window, &dir.join("back.png"), 60, drawn_again);
    if let Some(status) = viewer.0.try_wait().unwrap() {
        panic!("the viewer stopped: {status}: {}", stderr_of(&mut viewer.0));
    }
    assert!(
        drawn_again(&back),
        "the viewer did not draw again after the window came back"
    );

    escape_ends(&display, &window, &mut viewer);
}

#[test]
fn sun_keys_change_the_window() {
    // quarry_01 starts with its sun split out and its shadow on; the keys O (shadow off)
    // and U (the sun kept in the IBL) change the HUD's sun line to what the same tokens
    // give offscreen, waiting (polling the window) until the line shows it.
    let Some(_turn) = window_turn() else {
        return;
    };
    let dir = output_dir("view_window_sun");
    let quarry = ["tests/data/quarry_01_1k.hdr"];
    let (display, _xvfb, mut viewer, window) = open_window(&dir, &quarry, "quarry_01");
    let sun_line = splitsum::view::hud::line_box(4, SIZE.0);
    let expected = [
        offscreen(&dir, "expected_start.png", &quarry, "", 1),
        offscreen(&dir, "expected_o.png", &quarry, "o", 1),
        offscreen(&dir, "expected_o_u.png", &quarry, "o u", 1),
    ];
    // The line as offscreen (no glyph differs; the two present passes round a few steps
    // apart), and each line's text apart from the one before (measured: 30 glyph pixels
    // for "shadow on" → "shadow off", 509 for split → kept; bar 10).
    for (k, key) in ["", "o", "u"].into_iter().enumerate() {
        if k > 0 {
            let apart = glyph_differences(&expected[k], &expected[k - 1], sun_line);
            assert!(
                apart > 10,
                "key '{key}' changed {apart} glyph pixels of the line"
            );
            if k == 1 {
                // U held down while the window gains focus and let go: winit reports
                // the held key as a synthetic press, which is no press (a toggle there
                // would show the sun kept below, where only O was pressed).
                xdotool(&display, &["keydown", "u"]);
                xdotool(&display, &["windowfocus", "--sync", &window]);
                xdotool(&display, &["keyup", "u"]);
            }
            xdotool(&display, &["windowfocus", "--sync", &window]);
            xdotool(&display, &["key", key]);
        }
        let path = dir.join(format!("after_{k}.png"));
        let shot = capture_until(&display, &window, &path, 60, |s| {
            glyph_differences(s, &expected[k], sun_line) == 0
        });
        let d = glyph_differences(&shot, &expected[k], sun_line);
        assert_eq!(
            d, 0,
            "after key '{key}': {d} glyph pixels of the sun line differ"
        );
    }
    escape_ends(&display, &window, &mut viewer);
}
