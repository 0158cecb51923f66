//! The live window: a scene file simulated in real time on a thread of its
//! own and drawn through winit and wgpu.
//!
//! The simulation thread steps the world at the pace of the wall clock
//! times the time scale and holds the world's lock only while it steps.
//! The window thread draws: when the world is free it takes what a frame
//! needs from it (the render scene, the overlay's numbers), otherwise it
//! redraws the last one with the camera where the user has moved it, so a
//! slow simulation never holds up the interface. A window thread that has
//! not had the world for [`STARVED`] makes the simulation wait between two
//! steps until it has.
//!
//! Frames are rendered by [`SceneRenderer`] (offscreen, read back), the
//! overlay drawn on the CPU, and the image written into the window's
//! surface texture and presented.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant, SystemTime};

use nalgebra::Point3;
use soak_bake::Mesh;
use soak_rapier::scene::LoadedScene;
use soak_rapier::{SampleCsv, Simulation, convert};
use soak_shade::render::{RenderScene, adapter_label};
use winit::application::ApplicationHandler;
use winit::dpi::{PhysicalPosition, PhysicalSize};
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{Key, NamedKey};
use winit::window::{Window, WindowId};

use crate::error::ViewError;
use crate::frames::{FrameOptions, SceneRenderer, View};
use crate::orbit::{Orbit, pick};
use crate::overlay;

mod simulation;
mod window;

use self::simulation::{Shared, lock, simulate, with_world};
use self::window::{modified, read_back};

/// How long the window thread may go without the world before the
/// simulation waits for it between steps.
pub const STARVED: Duration = Duration::from_millis(40);

/// How long a wet body's liquid texture is drawn before it is made again
/// (a 1024² one costs about as much as a frame on a software adapter).
const LIQUID_EVERY: Duration = Duration::from_millis(500);

/// How long after an input the frames are drawn at half the window's
/// resolution (and scaled up), so that the camera follows the mouse on a
/// software adapter too.
const INTERACTIVE: Duration = Duration::from_millis(300);

/// How often the scene file's modification time is read.
const WATCH_EVERY: Duration = Duration::from_millis(400);

/// How far the simulation may fall behind the clock before the clock is
/// moved to it (it then runs slower than asked, and says so), s.
const MAX_LAG: f64 = 0.25;

/// How the viewer starts and, for tests and recordings, when it stops.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewOptions {
    /// Window size, pixels.
    pub size: (u32, u32),
    /// What the frames show.
    pub view: View,
    /// Weight and buoyancy arrows.
    pub forces: bool,
    /// Start running (otherwise paused).
    pub play: bool,
    /// Simulated seconds per wall-clock second.
    pub time_scale: f64,
    /// Show the overlay.
    pub overlay: bool,
    /// Reload the scene when its file changes.
    pub watch: bool,
    /// Advance this many steps before the window opens, then start paused
    /// (a reproducible frame, as `soak render --frame`).
    pub steps: Option<u64>,
    /// Close after this many frames.
    pub frames: Option<u64>,
    /// Close after this long (wall clock), whatever the frames.
    pub seconds: Option<f64>,
    /// Write the last frame presented (read back from the window's
    /// surface) as a PNG here when the viewer closes.
    pub screenshot: Option<PathBuf>,
    /// Write the bodies' time series here as CSV, the columns and the
    /// pace of `soak simulate --csv` (a row per body every `output.every`
    /// steps, handed to the file at least once a second and on close). The
    /// series starts when the window opens; a restart or a reload starts
    /// the time column again in the same file.
    pub csv: Option<PathBuf>,
}

impl Default for ViewOptions {
    fn default() -> Self {
        Self {
            size: (960, 540),
            view: View::Shaded,
            forces: false,
            play: true,
            time_scale: 1.0,
            overlay: true,
            watch: true,
            steps: None,
            frames: None,
            seconds: None,
            screenshot: None,
            csv: None,
        }
    }
}

/// What a viewing session measured.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ViewReport {
    /// Frames presented.
    pub frames: u64,
    /// Mean and largest time from the start of a frame to its present, ms.
    pub frame_ms: [f64; 2],
    /// Mean and largest time from an input event to the present of the
    /// frame showing it, ms (zero without input).
    pub input_to_frame_ms: [f64; 2],
    /// Mean time of a simulation step, ms.
    pub step_ms: f64,
    /// Simulated time at the end, s.
    pub time: f64,
    /// Simulated seconds per wall-clock second while playing.
    pub speed: f64,
    /// The adapter the frames were drawn on.
    pub adapter: String,
    /// The scene reloads, and those refused (the previous scene kept).
    pub reloads: [u64; 2],
    /// Why each refused reload was refused (the file and line where the
    /// scene's error has them), as the overlay showed it.
    pub refused: Vec<String>,
    /// The body selected at the end, by name.
    pub selected: Option<String>,
}

/// Shows the scene in `path` in a window until it is closed (or
/// [`ViewOptions::frames`] have been presented, or
/// [`ViewOptions::seconds`] have passed).
///
/// Keys: Space plays and pauses, `.` (or →) steps once, `+`/`-` double
/// and halve the time scale, `R` restarts, `1`–`4` show the shaded,
/// liquid, segments and normals views, `F` the force arrows, `H` hides the
/// overlay, Escape or `Q` quits. Mouse: left drag turns about the target,
/// right drag (or shift and left) pans, the wheel zooms, a click selects
/// the body under the cursor.
///
/// # Errors
/// A scene that does not load or build, no window (no display), no GPU
/// adapter that can draw to it, a screenshot that cannot be written.
pub fn run(path: &Path, options: ViewOptions) -> Result<ViewReport, ViewError> {
    let loaded = LoadedScene::from_file(path)?;
    let sim = Simulation::from_scene(&loaded)?;
    show(sim, Source::Scene(Box::new(loaded)), Some(path), options)
}

/// Shows a world of your own, as [`run`] shows a scene file: your Rapier
/// world with soak's generator, made a [`Simulation`] by
/// [`Simulation::from_parts`], and the mesh of each of its bodies (in
/// order; each in its body's local frame). The water drawn is the
/// generator's. `R` cannot rebuild such a world (it says so), and there is
/// no file to watch.
///
/// # Errors
/// [`ViewError::Meshes`] when there is not one mesh per body; a step that
/// fails in [`ViewOptions::steps`]; no window, no adapter that draws to it,
/// a screenshot that cannot be written.
pub fn run_world(
    sim: Simulation,
    meshes: Vec<Arc<Mesh>>,
    options: ViewOptions,
) -> Result<ViewReport, ViewError> {
    if meshes.len() != sim.bodies.len() {
        return Err(ViewError::Meshes {
            bodies: sim.bodies.len(),
            meshes: meshes.len(),
        });
    }
    show(sim, Source::World(meshes), None, options)
}

/// What the world was made from: a scene file (which can make it again),
/// or the meshes of a world of your own.
enum Source {
    Scene(Box<LoadedScene>),
    World(Vec<Arc<Mesh>>),
}

fn show(
    mut sim: Simulation,
    source: Source,
    path: Option<&Path>,
    options: ViewOptions,
) -> Result<ViewReport, ViewError> {
    let mut options = options;
    if let Some(steps) = options.steps {
        for _ in 0..steps {
            sim.step()?;
        }
        options.play = false;
    }
    let csv = match &options.csv {
        Some(path) => Some(SampleCsv::create(path).map_err(|source| ViewError::Csv {
            path: path.clone(),
            source,
        })?),
        None => None,
    };
    let shared = Arc::new(Shared::new(sim, source, &options));
    let worker = {
        let shared = Arc::clone(&shared);
        std::thread::Builder::new()
            .name("soak-view simulation".into())
            .spawn(move || {
                // The world steps on all cores but one, which is left to
                // the window (on a software adapter the rasteriser's).
                let threads =
                    std::thread::available_parallelism().map_or(1, |n| n.get().saturating_sub(1).max(1));
                match rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .thread_name(|i| format!("soak-view world {i}"))
                    .build()
                {
                    Ok(pool) => pool.install(|| simulate(&shared, csv)),
                    Err(_) => simulate(&shared, csv),
                }
            })
            .map_err(|e| ViewError::Window(format!("cannot start the simulation thread: {e}")))?
    };
    let event_loop = event_loop();
    let mut app = App::new(path, options, Arc::clone(&shared));
    let run = event_loop.and_then(|event_loop| {
        event_loop.set_control_flow(ControlFlow::Poll);
        event_loop
            .run_app(&mut app)
            .map_err(|e| ViewError::Window(e.to_string()))
    });
    lock(&shared.control).quit = true;
    let _ = worker.join();
    run?;
    if let Some(e) = app.error.take() {
        return Err(e);
    }
    let mut report = app.report;
    let stats = lock(&shared.stats).clone();
    report.step_ms = stats.step_ms;
    report.speed = stats.speed;
    report.time = lock(&shared.live).sim.time();
    Ok(report)
}

/// The event loop, on any thread where the platform allows it (a test's).
fn event_loop() -> Result<EventLoop<()>, ViewError> {
    let mut builder = EventLoop::builder();
    #[cfg(all(unix, not(target_os = "macos")))]
    {
        use winit::platform::x11::EventLoopBuilderExtX11 as _;
        builder.with_any_thread(true);
    }
    builder.build().map_err(|e| ViewError::Window(e.to_string()))
}

/// The window, its surface and what is drawn.
struct Gpu {
    window: Arc<Window>,
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    device: wgpu::Device,
    queue: wgpu::Queue,
    renderer: SceneRenderer,
    adapter: String,
}

/// What the last frame drew, kept for redraws while the world is busy.
struct Drawn {
    scene: RenderScene,
    generation: u64,
    time: f64,
    /// Per body: name, picking sphere (centre, radius), the overlay's line.
    bodies: Vec<(String, (Point3<f64>, f64), String)>,
}

struct App {
    /// The scene file, watched; `None` for a world of your own.
    path: Option<PathBuf>,
    options: ViewOptions,
    shared: Arc<Shared>,
    gpu: Option<Gpu>,
    drawn: Option<Drawn>,
    orbit: Option<Orbit>,
    selected: Option<usize>,
    cursor: PhysicalPosition<f64>,
    left: Option<PhysicalPosition<f64>>,
    right: bool,
    shift: bool,
    dragged: f64,
    /// When the oldest input not yet shown arrived.
    input: Option<Instant>,
    /// When the last input arrived.
    last_input: Option<Instant>,
    /// Overlay lines about reloads.
    notice: Option<String>,
    modified: Option<SystemTime>,
    watched: Instant,
    /// The last frame presented, as read back (only with a screenshot).
    last_frame: Option<image::RgbaImage>,
    /// When the first frame began.
    opened: Option<Instant>,
    report: ViewReport,
    frame_ms: Vec<f64>,
    input_ms: Vec<f64>,
    error: Option<ViewError>,
}

impl App {
    fn new(path: Option<&Path>, options: ViewOptions, shared: Arc<Shared>) -> Self {
        Self {
            path: path.map(Path::to_path_buf),
            modified: path.and_then(modified),
            options,
            shared,
            gpu: None,
            drawn: None,
            orbit: None,
            selected: None,
            cursor: PhysicalPosition::new(0.0, 0.0),
            left: None,
            right: false,
            shift: false,
            dragged: 0.0,
            input: None,
            last_input: None,
            notice: None,
            watched: Instant::now(),
            last_frame: None,
            opened: None,
            report: ViewReport::default(),
            frame_ms: Vec::new(),
            input_ms: Vec::new(),
            error: None,
        }
    }

    /// Stops the event loop on an error, kept for [`run`] to return.
    fn fail(&mut self, event_loop: &ActiveEventLoop, e: ViewError) {
        self.error.get_or_insert(e);
        event_loop.exit();
    }

    fn frame_options(&self, size: (u32, u32)) -> FrameOptions {
        FrameOptions {
            size,
            view: self.options.view,
            forces: self.options.forces,
            eye: None,
            target: None,
        }
    }

    /// Opens the window and the device that draws to it.
    fn open(&mut self, event_loop: &ActiveEventLoop) -> Result<Gpu, ViewError> {
        let (w, h) = self.options.size;
        let title = match &self.path {
            Some(path) => format!("soak view: {}", path.display()),
            None => "soak view".to_string(),
        };
        let window = event_loop
            .create_window(
                Window::default_attributes()
                    .with_title(title)
                    .with_inner_size(PhysicalSize::new(w.max(1), h.max(1))),
            )
            .map_err(|e| ViewError::Window(e.to_string()))?;
        let window = Arc::new(window);
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let surface = instance
            .create_surface(Arc::clone(&window))
            .map_err(|e| ViewError::Window(format!("no surface: {e}")))?;
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: Some(&surface),
            apply_limit_buckets: false,
        }))
        .map_err(|e| ViewError::Window(format!("no adapter draws to the window: {e}")))?;
        let info = adapter.get_info();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("soak view"),
            ..Default::default()
        }))
        .map_err(|e| ViewError::Window(format!("no device: {e}")))?;
        let caps = surface.get_capabilities(&adapter);
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| {
                matches!(
                    f,
                    wgpu::TextureFormat::Bgra8UnormSrgb | wgpu::TextureFormat::Rgba8UnormSrgb
                )
            })
            .ok_or_else(|| {
                ViewError::Window(format!("no 8-bit sRGB surface format in {:?}", caps.formats))
            })?;
        if !caps.usages.contains(wgpu::TextureUsages::COPY_DST) {
            return Err(ViewError::Window(
                "the window's surface cannot be written to (no COPY_DST)".into(),
            ));
        }
        let mut usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_DST;
        if self.options.screenshot.is_some() {
            if !caps.usages.contains(wgpu::TextureUsages::COPY_SRC) {
                return Err(ViewError::Window(
                    "the window's surface cannot be read back for a screenshot (no COPY_SRC)".into(),
                ));
            }
            usage |= wgpu::TextureUsages::COPY_SRC;
        }
        let size = window.inner_size();
        let config = wgpu::SurfaceConfiguration {
            usage,
            format,
            color_space: wgpu::SurfaceColorSpace::Auto,
            width: size.width.max(1),
            height: size.height.max(1),
            present_mode: if caps.present_modes.contains(&wgpu::PresentMode::Fifo) {
                wgpu::PresentMode::Fifo
            } else {
                caps.present_modes[0]
            },
            desired_maximum_frame_latency: 2,
            alpha_mode: caps.alpha_modes[0],
            view_formats: vec![],
        };
        surface.configure(&device, &config);
        let label = adapter_label(&info);
        let options = self.frame_options((config.width, config.height));
        let mut renderer = with_world(&self.shared, |live| match &live.source {
            Source::Scene(loaded) => {
                SceneRenderer::with_device(loaded, options, &device, &queue, label.clone())
            }
            Source::World(meshes) => {
                SceneRenderer::for_world(&live.sim, meshes.clone(), options, &device, &queue, label.clone())
            }
        })?;
        renderer.set_liquid_every(Some(LIQUID_EVERY));
        Ok(Gpu {
            window,
            surface,
            config,
            device,
            queue,
            renderer,
            adapter: label,
        })
    }

    /// Reloads the scene when its file changed: the new scene replaces the
    /// running one, or the error is shown and the running one kept.
    fn watch(&mut self) {
        let Some(path) = self.path.clone() else {
            return;
        };
        if !self.options.watch || self.watched.elapsed() < WATCH_EVERY {
            return;
        }
        self.watched = Instant::now();
        let now = modified(&path);
        if now == self.modified {
            return;
        }
        self.modified = now;
        let built = LoadedScene::from_file(&path)
            .map_err(ViewError::from)
            .and_then(|loaded| Ok((Simulation::from_scene(&loaded)?, loaded)));
        let rebuilt = built.and_then(|(sim, loaded)| {
            let renderer = match &self.gpu {
                Some(gpu) => {
                    let mut renderer = SceneRenderer::with_device(
                        &loaded,
                        self.frame_options((gpu.config.width, gpu.config.height)),
                        &gpu.device,
                        &gpu.queue,
                        gpu.adapter.clone(),
                    )?;
                    renderer.set_liquid_every(Some(LIQUID_EVERY));
                    Some(renderer)
                }
                None => None,
            };
            Ok((sim, loaded, renderer))
        });
        match rebuilt {
            Ok((sim, loaded, renderer)) => {
                with_world(&self.shared, |live| {
                    live.sim = sim;
                    live.source = Source::Scene(Box::new(loaded));
                    live.generation += 1;
                });
                if let (Some(gpu), Some(renderer)) = (self.gpu.as_mut(), renderer) {
                    gpu.renderer = renderer;
                }
                let mut stats = lock(&self.shared.stats);
                stats.error = None;
                stats.ended = false;
                self.drawn = None;
                self.selected = None;
                self.report.reloads[0] += 1;
                self.notice = Some(format!("reloaded {}", path.display()));
            }
            Err(e) => {
                self.report.reloads[1] += 1;
                self.report.refused.push(e.to_string());
                self.notice = Some(format!("reload failed, the previous scene runs: {e}"));
            }
        }
    }

    /// Takes a frame's state from the world if it is free and new.
    fn take_state(&mut self) {
        let Some(gpu) = self.gpu.as_mut() else {
            return;
        };
        let guard = self.shared.live.try_lock();
        let live = match guard {
            Ok(live) => live,
            Err(std::sync::TryLockError::Poisoned(p)) => p.into_inner(),
            Err(std::sync::TryLockError::WouldBlock) => {
                lock(&self.shared.control)
                    .wanted_since
                    .get_or_insert_with(Instant::now);
                return;
            }
        };
        lock(&self.shared.control).wanted_since = None;
        if self
            .drawn
            .as_ref()
            .is_some_and(|d| d.generation == live.generation)
        {
            return;
        }
        let sim = &live.sim;
        let scene = gpu.renderer.scene(sim);
        let reports = sim.report();
        let mut bodies = Vec::new();
        for (i, (b, r)) in sim.bodies.iter().zip(&reports).enumerate() {
            let centre = sim
                .world
                .bodies
                .get(b.handle)
                .map(|rb| Point3::from(convert::pose(rb.position()).translation.vector))
                .unwrap_or_else(Point3::origin);
            let mut line = format!(
                "{}: submerged {:.1} %, mass {:.2} kg",
                r.name,
                100.0 * r.submerged_fraction,
                r.mass
            );
            if let Some(v) = r.liquid_inside {
                line += &format!(", inside {v:.4} m3");
            }
            if let Some(v) = r.surface_liquid {
                line += &format!(", surface liquid {v:.2e} m3");
            }
            bodies.push((b.name.clone(), (centre, gpu.renderer.radius(i)), line));
        }
        if self.orbit.is_none() {
            self.orbit = Some(Orbit::looking(scene.camera.eye, scene.camera.target));
        }
        self.drawn = Some(Drawn {
            scene,
            generation: live.generation,
            time: sim.time(),
            bodies,
        });
    }

    /// The overlay's lines.
    fn overlay(&self, frame_ms: f64) -> Vec<String> {
        let control = *lock(&self.shared.control);
        let stats = lock(&self.shared.stats).clone();
        let t = self.drawn.as_ref().map_or(0.0, |d| d.time);
        let state = if stats.ended {
            "end of scene (R restarts)".to_string()
        } else if control.play {
            let mut s = format!("playing x{}", control.time_scale);
            if stats.behind {
                s += &format!(" - SLOWER: the world runs at x{:.2}", stats.speed);
            }
            s
        } else {
            "paused".to_string()
        };
        // The adapter's name without its details.
        let adapter = self
            .gpu
            .as_ref()
            .map_or("", |g| g.adapter.split(" (").next().unwrap_or_default());
        let mut lines = vec![
            format!("t = {t:.2} s  {state}"),
            format!(
                "frame {frame_ms:.0} ms  step {:.1} ms  [{adapter}]",
                stats.step_ms
            ),
            format!(
                "view {:?}{}  keys 1-4 F Space . + - R H Q",
                self.options.view,
                if self.options.forces { " + forces" } else { "" }
            ),
        ];
        if let (Some(i), Some(d)) = (self.selected, &self.drawn)
            && let Some((_, _, line)) = d.bodies.get(i)
        {
            lines.push(line.clone());
        } else {
            lines.push("click a body to select it".into());
        }
        if let Some(e) = &stats.error {
            lines.push(e.clone());
        }
        if let Some(n) = &self.notice {
            // Long errors wrapped at 100 characters.
            let chars: Vec<char> = n.chars().collect();
            for chunk in chars.chunks(100) {
                lines.push(chunk.iter().collect());
            }
        }
        lines
    }

    /// Renders, draws the overlay and presents one frame.
    fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        let start = Instant::now();
        self.watch();
        self.take_state();
        let Some(mut scene) = self.drawn.as_ref().map(|d| d.scene.clone()) else {
            return;
        };
        if let Some(orbit) = &self.orbit {
            scene.camera = orbit.camera();
        }
        let last_ms = self.frame_ms.last().copied().unwrap_or(0.0);
        let lines = if self.options.overlay {
            self.overlay(last_ms)
        } else {
            Vec::new()
        };
        let moving = self.last_input.is_some_and(|t| t.elapsed() < INTERACTIVE);
        let Some(gpu) = self.gpu.as_mut() else {
            return;
        };
        let full = (gpu.config.width, gpu.config.height);
        let size = if moving {
            ((full.0 / 2).max(1), (full.1 / 2).max(1))
        } else {
            full
        };
        if gpu.renderer.options().size != size {
            let options = FrameOptions {
                size,
                ..gpu.renderer.options().clone()
            };
            if let Err(e) = gpu.renderer.set_options(options) {
                return self.fail(event_loop, e);
            }
        }
        let mut image = match gpu.renderer.render(&scene) {
            Ok(image) => image,
            Err(e) => return self.fail(event_loop, e),
        };
        if image.dimensions() != full {
            image = image::imageops::resize(&image, full.0, full.1, image::imageops::FilterType::Nearest);
        }
        overlay::draw(&mut image, &lines);
        let frame = match gpu.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(f) | wgpu::CurrentSurfaceTexture::Suboptimal(f) => f,
            other => {
                // Lost or outdated: configure again and draw next time.
                log::debug!("surface: {other:?}");
                gpu.surface.configure(&gpu.device, &gpu.config);
                return;
            }
        };
        let (w, h) = image.dimensions();
        let size = frame.texture.size();
        if (size.width, size.height) != (w, h) {
            // The window was resized since the frame was rendered.
            drop(frame);
            return;
        }
        let bgra = gpu.config.format == wgpu::TextureFormat::Bgra8UnormSrgb;
        let mut bytes = image.into_raw();
        if bgra {
            for p in bytes.chunks_exact_mut(4) {
                p.swap(0, 2);
            }
        }
        gpu.queue.write_texture(
            frame.texture.as_image_copy(),
            &bytes,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(4 * w),
                rows_per_image: Some(h),
            },
            size,
        );
        if self.options.screenshot.is_some() {
            match read_back(&gpu.device, &gpu.queue, &frame.texture, bgra) {
                Ok(image) => self.last_frame = Some(image),
                Err(e) => return self.fail(event_loop, e),
            }
        }
        gpu.window.pre_present_notify();
        gpu.queue.present(frame);
        let ms = start.elapsed().as_secs_f64() * 1e3;
        self.frame_ms.push(ms);
        if let Some(at) = self.input.take() {
            self.input_ms.push(at.elapsed().as_secs_f64() * 1e3);
        }
        self.report.frames += 1;
        let opened = *self.opened.get_or_insert(start);
        if self.options.frames.is_some_and(|n| self.report.frames >= n)
            || self
                .options
                .seconds
                .is_some_and(|s| opened.elapsed().as_secs_f64() >= s)
        {
            event_loop.exit();
        }
    }

    fn on_key(&mut self, key: &Key) {
        let mut control = lock(&self.shared.control);
        match key {
            Key::Named(NamedKey::Space) => control.play = !control.play,
            Key::Named(NamedKey::ArrowRight) => {
                control.play = false;
                control.single_steps += 1;
            }
            Key::Character(c) => match c.as_str() {
                "." => {
                    control.play = false;
                    control.single_steps += 1;
                }
                "+" | "=" => control.time_scale = (control.time_scale * 2.0).min(1024.0),
                "-" => control.time_scale = (control.time_scale / 2.0).max(1.0 / 1024.0),
                "r" | "R" => {
                    control.restart = true;
                    control.play = true;
                }
                "1" => self.options.view = View::Shaded,
                "2" => self.options.view = View::Liquid,
                "3" => self.options.view = View::Segments,
                "4" => self.options.view = View::Normals,
                "f" | "F" => self.options.forces = !self.options.forces,
                "h" | "H" => self.options.overlay = !self.options.overlay,
                _ => return,
            },
            _ => return,
        }
        drop(control);
        self.apply_frame_options();
        self.touched();
    }

    /// Hands the view and arrows to the renderer (the next state taken
    /// shows them).
    fn apply_frame_options(&mut self) {
        if let Some(gpu) = self.gpu.as_mut() {
            let options = FrameOptions {
                view: self.options.view,
                forces: self.options.forces,
                ..gpu.renderer.options().clone()
            };
            if options != *gpu.renderer.options() {
                if let Err(e) = gpu.renderer.set_options(options) {
                    self.error.get_or_insert(e);
                }
                // Build the scene again with them.
                self.drawn = self.drawn.take().map(|d| Drawn {
                    generation: u64::MAX,
                    ..d
                });
            }
        }
    }
}
