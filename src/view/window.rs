//! The viewer's window: winit's event loop (X11), a wgpu surface on an adapter that can
//! present to it, and [`Viewer`] drawing into it every frame. Keys are polled each frame as
//! LearnOpenGL's `processInput` does; the mouse turns the camera while the cursor is
//! captured, with LearnOpenGL's `firstMouse` guard so that a re-capture does not jump.
//! A dropped .hdr/.exr is baked on another thread (progress in the HUD) and replaces the
//! light when done; a bad one is a HUD line and a line on stderr, and the view goes on.

use std::collections::HashSet;
use std::path::PathBuf;
use std::sync::mpsc::{channel, Receiver, Sender};
use std::sync::Arc;
use std::time::Instant;

use winit::application::ApplicationHandler;
use winit::event::{ElementState, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{KeyCode, ModifiersState, PhysicalKey};
use winit::window::{CursorGrabMode, Window, WindowId};

use crate::gpu::context::GpuContext;
use crate::view::frame::ViewLight;
use crate::view::gpu::GpuRenderer;
use crate::view::model::Model;
use crate::view::session::{Renderer, Viewer, DEFAULT_POINTS_PER_ESTIMATE};
use crate::view::state::{Action, Change};
use crate::view::{load_light, screenshot_path, LightSource, ViewOptions};
use crate::{Error, Result};

/// What the baking thread reports.
enum Baking {
    /// A stage started.
    Progress(String),
    /// The light is ready.
    Done(Box<ViewLight>),
    /// It failed.
    Failed(String),
}

/// Bakes `source` on a thread of its own, reporting on the returned channel.
fn bake_in_background(source: LightSource, opts: &ViewOptions) -> Receiver<Baking> {
    let (tx, rx) = channel();
    let (backend, sun) = (opts.backend, opts.sun);
    std::thread::spawn(move || {
        let progress_tx: Sender<Baking> = tx.clone();
        let mut progress = |what: String| {
            let _ = progress_tx.send(Baking::Progress(what));
        };
        let message = match load_light(&source, backend, sun, &mut progress) {
            Ok(light) => Baking::Done(Box::new(light)),
            Err(e) => Baking::Failed(e.to_string()),
        };
        let _ = tx.send(message);
    });
    rx
}

/// The window and what draws into it.
struct Running {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    context: GpuContext,
    viewer: Viewer,
    format: wgpu::TextureFormat,
}

struct App {
    opts: ViewOptions,
    /// The models, loaded before the window opens; moved into the viewer when it starts.
    models: Vec<Model>,
    running: Option<Running>,
    error: Option<Error>,
    baking: Option<Receiver<Baking>>,
    held: HashSet<KeyCode>,
    modifiers: ModifiersState,
    captured: bool,
    last_cursor: Option<(f64, f64)>,
    last_frame: Instant,
    screenshots: u32,
}

impl App {
    fn start(&mut self, event_loop: &ActiveEventLoop) -> Result<Running> {
        let window_error = |message: String| Error::Window { message };
        let attributes = Window::default_attributes()
            .with_title("splitsum view")
            .with_inner_size(winit::dpi::PhysicalSize::new(
                self.opts.size.0,
                self.opts.size.1,
            ));
        let window = Arc::new(
            event_loop
                .create_window(attributes)
                .map_err(|e| window_error(format!("cannot open a window: {e}")))?,
        );
        let display = event_loop.owned_display_handle();
        let instance = wgpu::Instance::new(
            wgpu::InstanceDescriptor::new_with_display_handle_from_env(Box::new(display)),
        );
        let surface = instance
            .create_surface(window.clone())
            .map_err(|e| window_error(format!("cannot draw into the window: {e}")))?;
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: Some(&surface),
            apply_limit_buckets: false,
        }))
        .map_err(|e| Error::NoAdapter {
            reason: format!("none can draw into the window: {e}"),
        })?;
        let context = GpuContext::from_adapter(&adapter)?;
        let caps = surface.get_capabilities(&adapter);
        // A plain 8-bit format gets the encoded values as they are (the same bytes as a
        // screenshot); an sRGB one gets linear values back from the present pass.
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| {
                !f.is_srgb()
                    && matches!(
                        f,
                        wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Rgba8Unorm
                    )
            })
            .or_else(|| caps.formats.first().copied())
            .ok_or_else(|| window_error("the window's surface offers no format".into()))?;
        let size = window.inner_size();
        let config = wgpu::SurfaceConfiguration {
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            format,
            width: size.width.max(1),
            height: size.height.max(1),
            present_mode: wgpu::PresentMode::AutoVsync,
            desired_maximum_frame_latency: 2,
            alpha_mode: caps
                .alpha_modes
                .first()
                .copied()
                .unwrap_or(wgpu::CompositeAlphaMode::Auto),
            view_formats: vec![],
            color_space: wgpu::SurfaceColorSpace::Auto,
        };
        if size.width > 0 && size.height > 0 {
            surface.configure(&context.device, &config);
        }
        let renderer = GpuRenderer::new(context.device.clone(), context.queue.clone())?;
        let mut viewer = Viewer::new(
            ViewLight::blank(),
            std::mem::take(&mut self.models),
            Renderer::Gpu(Box::new(renderer)),
            context.adapter_description(),
        )?;
        self.opts.initial_state(&mut viewer)?;
        Ok(Running {
            window,
            surface,
            config,
            context,
            viewer,
            format,
        })
    }

    /// The window's key for an action, or the held movement keys.
    fn action(&self, key: KeyCode) -> Option<Action> {
        let shift = self.modifiers.shift_key();
        Some(match key {
            KeyCode::Digit1 => Action::Material(0),
            KeyCode::Digit2 => Action::Material(1),
            KeyCode::Digit3 => Action::Material(2),
            KeyCode::Digit4 => Action::Material(3),
            KeyCode::Digit5 => Action::Material(4),
            KeyCode::Digit6 => Action::Material(5),
            KeyCode::Digit7 => Action::Model(0),
            KeyCode::Digit8 => Action::Model(1),
            KeyCode::Digit9 => Action::Model(2),
            KeyCode::Digit0 => Action::Model(3),
            KeyCode::Tab if shift => Action::PreviousModel,
            KeyCode::Tab => Action::NextModel,
            KeyCode::KeyR => Action::RougherBy,
            KeyCode::KeyF => Action::SmootherBy,
            KeyCode::KeyT => Action::ToggleMetallic,
            KeyCode::Equal | KeyCode::NumpadAdd => Action::Brighter,
            KeyCode::Minus | KeyCode::NumpadSubtract => Action::Darker,
            KeyCode::KeyG => Action::ToggleTruth,
            KeyCode::KeyH => Action::ToggleHeat,
            KeyCode::KeyL => Action::ToggleLights,
            KeyCode::KeyU => Action::ToggleSun,
            KeyCode::KeyO => Action::ToggleShadow,
            KeyCode::F1 => Action::ToggleHud,
            KeyCode::KeyP => Action::Screenshot,
            KeyCode::Escape => Action::Quit,
            _ => return None,
        })
    }

    fn capture(&mut self, on: bool) {
        let Some(r) = &self.running else { return };
        if on {
            let grabbed = r
                .window
                .set_cursor_grab(CursorGrabMode::Locked)
                .or_else(|_| r.window.set_cursor_grab(CursorGrabMode::Confined));
            if grabbed.is_err() {
                return;
            }
            r.window.set_cursor_visible(false);
            // LearnOpenGL's firstMouse: the first position after a capture only sets the
            // reference, so the view does not jump.
            self.last_cursor = None;
        } else {
            let _ = r.window.set_cursor_grab(CursorGrabMode::None);
            r.window.set_cursor_visible(true);
        }
        self.captured = on;
    }

    fn screenshot(&mut self) {
        let Some(r) = &mut self.running else { return };
        self.screenshots += 1;
        let path = PathBuf::from(format!("splitsum-view-{}.png", self.screenshots));
        let size = (r.config.width, r.config.height);
        let result = r
            .viewer
            .render_image(size)
            .and_then(|img| screenshot_path(&path, &img));
        let line = match result {
            Ok(()) => format!("saved {}", path.display()),
            Err(e) => format!("screenshot failed: {e}"),
        };
        eprintln!("{line}");
        r.viewer.message(line);
    }

    fn poll_baking(&mut self) {
        let Some(rx) = &self.baking else { return };
        let mut finished = false;
        while let Ok(msg) = rx.try_recv() {
            let Some(r) = &mut self.running else { return };
            match msg {
                Baking::Progress(what) => r.viewer.message(what),
                Baking::Done(light) => {
                    let name = light.name.clone();
                    match r.viewer.set_light(*light) {
                        Ok(()) => {
                            // The title names what is shown (a script can wait for it).
                            r.window.set_title(&format!("splitsum view · {name}"));
                            r.viewer.message(format!("showing {name}"));
                        }
                        Err(e) => {
                            eprintln!("error: {e}");
                            r.viewer.message(format!("error: {e}"));
                        }
                    }
                    finished = true;
                }
                Baking::Failed(e) => {
                    eprintln!("error: {e}");
                    r.viewer.message(format!("error: {e}"));
                    finished = true;
                }
            }
        }
        if finished {
            self.baking = None;
        }
    }

    fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        self.poll_baking();
        let dt = self.last_frame.elapsed().as_secs_f32().min(0.25);
        self.last_frame = Instant::now();
        let forward = [(KeyCode::KeyW, 1.0), (KeyCode::KeyS, -1.0)]
            .iter()
            .filter(|(k, _)| self.held.contains(k))
            .map(|(_, v)| v)
            .sum::<f32>();
        let sideways = [(KeyCode::KeyD, 1.0), (KeyCode::KeyA, -1.0)]
            .iter()
            .filter(|(k, _)| self.held.contains(k))
            .map(|(_, v)| v)
            .sum::<f32>();
        let Some(r) = &mut self.running else { return };
        if forward != 0.0 || sideways != 0.0 {
            r.viewer.state.camera.walk(forward, sideways, dt);
        }
        if r.config.width == 0 || r.config.height == 0 {
            return;
        }
        let texture = match r.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t)
            | wgpu::CurrentSurfaceTexture::Suboptimal(t) => t,
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => return,
            wgpu::CurrentSurfaceTexture::Outdated | wgpu::CurrentSurfaceTexture::Lost => {
                // Reconfigure and try again next frame.
                r.surface.configure(&r.context.device, &r.config);
                return;
            }
            other => {
                self.error = Some(Error::Window {
                    message: format!("the window's surface failed: {other:?}"),
                });
                event_loop.exit();
                return;
            }
        };
        let view = texture.texture.create_view(&Default::default());
        let size = (r.config.width, r.config.height);
        if let Err(e) = r.viewer.render_to(size, (&view, r.format)) {
            self.error = Some(r.context.lost_reason().map_or(e, |reason| Error::Gpu {
                stage: "viewer".into(),
                message: reason,
            }));
            event_loop.exit();
            return;
        }
        r.window.pre_present_notify();
        r.context.queue.present(texture);
        adapt_truth_points(&mut r.viewer);
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.running.is_some() {
            return;
        }
        match self.start(event_loop) {
            Ok(r) => {
                self.running = Some(r);
                let source = self.opts.light_source();
                self.baking = Some(bake_in_background(source, &self.opts));
            }
            Err(e) => {
                self.error = Some(e);
                event_loop.exit();
            }
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                if let Some(r) = &mut self.running {
                    r.config.width = size.width;
                    r.config.height = size.height;
                    // A minimised window is 0 × 0: nothing is drawn until it comes back.
                    if size.width > 0 && size.height > 0 {
                        r.surface.configure(&r.context.device, &r.config);
                    }
                }
            }
            WindowEvent::ModifiersChanged(m) => self.modifiers = m.state(),
            WindowEvent::KeyboardInput {
                event,
                is_synthetic,
                ..
            } => {
                let PhysicalKey::Code(code) = event.physical_key else {
                    return;
                };
                if event.state == ElementState::Released {
                    self.held.remove(&code);
                    return;
                }
                self.held.insert(code);
                // A synthetic press is a key already down when the window gained focus
                // (winit reports it, then the key's own press if it was on its way): it
                // holds a movement key but is not a press, or a toggle would run twice.
                if event.repeat || is_synthetic {
                    return;
                }
                match code {
                    KeyCode::KeyC => return self.capture(true),
                    KeyCode::KeyV => return self.capture(false),
                    _ => {}
                }
                let Some(action) = self.action(code) else {
                    return;
                };
                let Some(r) = &mut self.running else { return };
                match r.viewer.apply(action) {
                    Ok(Change::Quit) => event_loop.exit(),
                    Ok(Change::Screenshot) => self.screenshot(),
                    Ok(_) => {}
                    Err(e) => {
                        eprintln!("error: {e}");
                        r.viewer.message(format!("error: {e}"));
                    }
                }
            }
            WindowEvent::CursorMoved { position, .. } => {
                if !self.captured {
                    return;
                }
                if let (Some((x, y)), Some(r)) = (self.last_cursor, &mut self.running) {
                    r.viewer
                        .state
                        .camera
                        .look((position.x - x) as f32, (position.y - y) as f32);
                }
                self.last_cursor = Some((position.x, position.y));
            }
            WindowEvent::DroppedFile(path) => {
                if self.baking.is_some() {
                    if let Some(r) = &mut self.running {
                        r.viewer
                            .message("still baking the last file; drop again when it is done");
                    }
                    return;
                }
                if let Some(r) = &mut self.running {
                    r.viewer.message(format!("baking {}", path.display()));
                }
                self.baking = Some(bake_in_background(LightSource::File(path), &self.opts));
            }
            WindowEvent::RedrawRequested => self.redraw(event_loop),
            _ => {}
        }
    }

    fn about_to_wait(&mut self, _: &ActiveEventLoop) {
        if let Some(r) = &self.running {
            r.window.request_redraw();
        }
    }
}

/// Keeps a truth frame near [`TRUTH_FRAME_SECONDS`] so the window stays responsive:
/// halves the points of an estimate after a slow frame, doubles them after a fast one.
fn adapt_truth_points(viewer: &mut Viewer) {
    if viewer.state.mode == crate::view::frame::Mode::SplitSum {
        return;
    }
    let t = viewer.frame_seconds();
    let p = viewer.points_per_estimate;
    viewer.points_per_estimate = if t > 2.0 * TRUTH_FRAME_SECONDS {
        (p / 2).max(1)
    } else if t < 0.5 * TRUTH_FRAME_SECONDS {
        (p * 2).min(DEFAULT_POINTS_PER_ESTIMATE)
    } else {
        p
    };
}

/// The frame time the truth aims at in the window, seconds.
const TRUTH_FRAME_SECONDS: f32 = 0.05;

/// Whether this process can reach a display at all (on Linux and the BSDs: `DISPLAY` or
/// `WAYLAND_DISPLAY` is set).
pub fn display_available() -> bool {
    if cfg!(any(
        target_os = "linux",
        target_os = "freebsd",
        target_os = "openbsd",
        target_os = "netbsd"
    )) {
        ["DISPLAY", "WAYLAND_DISPLAY"]
            .iter()
            .any(|v| std::env::var_os(v).is_some_and(|s| !s.is_empty()))
    } else {
        true
    }
}

/// Opens the window on `models` and runs until Escape or the window closes.
pub fn run_window(opts: ViewOptions, models: Vec<Model>) -> Result<()> {
    if !display_available() {
        return Err(Error::NoDisplay);
    }
    let event_loop = EventLoop::new().map_err(|e| Error::Window {
        message: format!("cannot reach the display: {e}"),
    })?;
    event_loop.set_control_flow(ControlFlow::Poll);
    let mut app = App {
        opts,
        models,
        running: None,
        error: None,
        baking: None,
        held: HashSet::new(),
        modifiers: ModifiersState::empty(),
        captured: false,
        last_cursor: None,
        last_frame: Instant::now(),
        screenshots: 0,
    };
    event_loop.run_app(&mut app).map_err(|e| Error::Window {
        message: format!("the window's event loop failed: {e}"),
    })?;
    match app.error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}
