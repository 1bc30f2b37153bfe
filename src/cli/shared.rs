//! What the commands share: the baker they open, and how they tell the user what happened
//! (warnings, a progress bar, the line that says where the sun went).

use std::io::IsTerminal;
use std::path::Path;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use splitsum::{BackendJob, BakeOptions, Baker, SunMode, MIN_SUN_SHARE};

use super::args::CommonArgs;
use super::for_user;

/// A baker for `command` with `opts`, its backend note printed and, with -v, where `job`
/// runs.
pub(super) fn open_baker(
    command: &str,
    mut opts: BakeOptions,
    common: &CommonArgs,
    job: BackendJob,
) -> anyhow::Result<Baker> {
    opts.backend = common.backend.into();
    let baker = Baker::new(opts).map_err(|e| for_user(command, e))?;
    if let Some(note) = baker.backend_note() {
        eprintln!("note: {note}");
    }
    if common.verbose {
        eprintln!("backend: {}", baker.backend_description(job));
    }
    Ok(baker)
}

/// Prints warnings, one line each.
pub(super) fn warn(warnings: impl IntoIterator<Item = String>) {
    for w in warnings {
        eprintln!("warning: {w}");
    }
}

/// A progress bar on stderr when it is a terminal and `show` (hidden otherwise).
pub(super) fn progress_bar(show: bool, len: u64, template: &str) -> ProgressBar {
    let bar = ProgressBar::new(len);
    bar.set_draw_target(if show && std::io::stderr().is_terminal() {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::hidden()
    });
    if let Ok(style) = ProgressStyle::with_template(template) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}

/// What became of the sun (and further compact lights) of `input` in `mode`, in one line
/// (`light` names the file the lights went to); none for an environment without a sun
/// baked as it is.
pub(super) fn sun_line(
    input: &Path,
    lights: &[splitsum::Sun],
    mode: SunMode,
    light: &str,
) -> Option<String> {
    let input = input.display();
    let more = match lights.len() {
        0 | 1 => String::new(),
        n => format!(
            " and {} more compact light{} ({:.1} % of the light)",
            n - 1,
            if n > 2 { "s" } else { "" },
            100.0 * lights[1..].iter().map(|l| l.share).sum::<f32>()
        ),
    };
    // The first light is the sun, or a studio's lamp (an area light, whose shape it gives).
    let first = |l: &splitsum::Sun| match l.shape {
        Some(_) => "brightest light",
        None => "sun",
    };
    Some(match (lights.first(), mode) {
        (Some(sun), SunMode::Keep) => format!(
            "{input}: {} at {sun}{more}; baked into the IBL (--sun split writes them as lights, the first with shadows)",
            first(sun)
        ),
        (Some(sun), SunMode::Split) => format!(
            "{input}: {} at {sun}{more}; taken out of the IBL, written as {light}",
            first(sun)
        ),
        (None, SunMode::Keep) => return None,
        (None, SunMode::Split) => format!(
            "{input}: no sun (no compact source holds {:.0} % of the light): nothing taken out, no light written",
            100.0 * MIN_SUN_SHARE
        ),
    })
}
