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
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant, SystemTime};

use nalgebra::Point3;
use soak_bake::Mesh;
use soak_rapier::scene::LoadedScene;
use soak_rapier::{Simulation, convert};
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
                    Ok(pool) => pool.install(|| simulate(&shared)),
                    Err(_) => simulate(&shared),
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

/// The world and what it was made from.
struct Live {
    sim: Simulation,
    source: Source,
    /// Bumped by each step, restart and reload: a frame's state is new when
    /// it differs.
    generation: u64,
}

/// What the window asks of the simulation thread.
#[derive(Clone, Copy, Debug)]
struct Control {
    play: bool,
    time_scale: f64,
    single_steps: u32,
    restart: bool,
    quit: bool,
    /// When the window thread began to wait for the world, if it does.
    wanted_since: Option<Instant>,
    /// The window thread needs the world now (to open, reload): no step
    /// starts until it has had it.
    hold: bool,
}

/// What the simulation thread reports.
#[derive(Clone, Debug, Default)]
struct Stats {
    /// Mean step, ms, over the recent steps.
    step_ms: f64,
    /// Simulated over wall-clock seconds while playing, recently.
    speed: f64,
    /// Whether it fell behind the clock (slower than asked).
    behind: bool,
    /// The last step's error, if the simulation stopped on one.
    error: Option<String>,
    /// Whether it paused at the scene's end.
    ended: bool,
}

struct Shared {
    live: Mutex<Live>,
    control: Mutex<Control>,
    stats: Mutex<Stats>,
}

impl Shared {
    fn new(sim: Simulation, source: Source, options: &ViewOptions) -> Self {
        Self {
            live: Mutex::new(Live {
                sim,
                source,
                generation: 0,
            }),
            control: Mutex::new(Control {
                play: options.play,
                time_scale: options.time_scale,
                single_steps: 0,
                restart: false,
                quit: false,
                wanted_since: None,
                hold: false,
            }),
            stats: Mutex::new(Stats::default()),
        }
    }
}

/// A lock that a panic elsewhere does not poison for good.
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// `f` on the world as soon as the step in progress (if any) ends: the
/// simulation thread starts no step meanwhile (the world's lock is not
/// fair, and it would take it back between two steps).
fn with_world<R>(shared: &Shared, f: impl FnOnce(&mut Live) -> R) -> R {
    lock(&shared.control).hold = true;
    let r = f(&mut lock(&shared.live));
    lock(&shared.control).hold = false;
    r
}

/// The simulation thread: steps at the clock's pace while playing.
fn simulate(shared: &Shared) {
    // The clock: simulated time `anchor.1` at wall time `anchor.0`.
    let mut anchor: Option<(Instant, f64)> = None;
    let mut recent: Vec<(Instant, f64, f64)> = Vec::new(); // (wall, sim time, step ms)
    loop {
        let control = *lock(&shared.control);
        if control.quit {
            return;
        }
        if control.restart {
            let mut live = lock(&shared.live);
            let rebuilt = match &live.source {
                Source::Scene(loaded) => {
                    Simulation::from_scene(loaded).map_err(|e| format!("restart failed: {e}"))
                }
                Source::World(_) => Err("a world of your own cannot be built again: no restart".to_string()),
            };
            let mut stats = lock(&shared.stats);
            match rebuilt {
                Ok(sim) => {
                    live.sim = sim;
                    live.generation += 1;
                    stats.error = None;
                    stats.ended = false;
                }
                Err(e) => stats.error = Some(e),
            }
            lock(&shared.control).restart = false;
            anchor = None;
            continue;
        }
        let stepping = control.single_steps > 0;
        if !control.play && !stepping {
            anchor = None;
            std::thread::sleep(Duration::from_millis(4));
            continue;
        }
        // Waiting for the window thread to take a frame's state, or for
        // it to be done with the world.
        if control.hold || control.wanted_since.is_some_and(|t| t.elapsed() > STARVED) {
            std::thread::sleep(Duration::from_millis(1));
            continue;
        }
        let mut live = lock(&shared.live);
        let now = Instant::now();
        let sim_time = live.sim.time();
        if !stepping {
            if sim_time >= live.sim.duration {
                drop(live);
                lock(&shared.control).play = false;
                lock(&shared.stats).ended = true;
                continue;
            }
            let (wall, at) = *anchor.get_or_insert((now, sim_time));
            let due = at + (now - wall).as_secs_f64() * control.time_scale;
            if sim_time > due {
                drop(live);
                let ahead = (sim_time - due) / control.time_scale.max(1e-6);
                std::thread::sleep(Duration::from_secs_f64(ahead.min(0.01)));
                continue;
            }
            let behind = due - sim_time > MAX_LAG * control.time_scale;
            if behind {
                anchor = Some((now, sim_time));
            }
            lock(&shared.stats).behind = behind;
        }
        let start = Instant::now();
        let result = live.sim.step();
        let step_ms = start.elapsed().as_secs_f64() * 1e3;
        live.generation += 1;
        let t = live.sim.time();
        drop(live);
        if stepping {
            let mut c = lock(&shared.control);
            c.single_steps = c.single_steps.saturating_sub(1);
            anchor = None;
        }
        recent.push((Instant::now(), t, step_ms));
        recent.retain(|(w, _, _)| w.elapsed() < Duration::from_secs(1));
        let mut stats = lock(&shared.stats);
        stats.step_ms = recent.iter().map(|r| r.2).sum::<f64>() / recent.len() as f64;
        if let (Some(first), Some(last)) = (recent.first(), recent.last()) {
            let wall = (last.0 - first.0).as_secs_f64();
            if wall > 0.1 && !stepping {
                stats.speed = (last.1 - first.1) / wall;
            }
        }
        if let Err(e) = result {
            stats.error = Some(format!("the simulation stopped: {e}"));
            drop(stats);
            lock(&shared.control).play = false;
        }
    }
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

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.gpu.is_some() {
            return;
        }
        match self.open(event_loop) {
            Ok(gpu) => {
                self.report.adapter = gpu.adapter.clone();
                gpu.window.request_redraw();
                self.gpu = Some(gpu);
            }
            Err(e) => self.fail(event_loop, e),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => {
                if let Some(gpu) = self.gpu.as_mut()
                    && size.width > 0
                    && size.height > 0
                {
                    gpu.config.width = size.width;
                    gpu.config.height = size.height;
                    gpu.surface.configure(&gpu.device, &gpu.config);
                    let options = FrameOptions {
                        size: (size.width, size.height),
                        ..gpu.renderer.options().clone()
                    };
                    if let Err(e) = gpu.renderer.set_options(options) {
                        self.fail(event_loop, e);
                    }
                }
            }
            WindowEvent::RedrawRequested => self.redraw(event_loop),
            WindowEvent::ModifiersChanged(m) => self.shift = m.state().shift_key(),
            WindowEvent::KeyboardInput { event, .. } if event.state == ElementState::Pressed => {
                match &event.logical_key {
                    Key::Named(NamedKey::Escape) => event_loop.exit(),
                    Key::Character(c) if c.as_str() == "q" || c.as_str() == "Q" => event_loop.exit(),
                    key => self.on_key(key),
                }
            }
            WindowEvent::MouseInput { state, button, .. } => match (button, state) {
                (MouseButton::Left, ElementState::Pressed) => {
                    self.left = Some(self.cursor);
                    self.dragged = 0.0;
                }
                (MouseButton::Left, ElementState::Released) => {
                    // A click, not the end of a drag, selects.
                    let clicked = self.left.take().is_some() && self.dragged < 4.0;
                    if clicked {
                        self.select();
                    }
                }
                (MouseButton::Right, state) => self.right = state == ElementState::Pressed,
                _ => {}
            },
            WindowEvent::CursorMoved { position, .. } => {
                let (dx, dy) = (position.x - self.cursor.x, position.y - self.cursor.y);
                self.cursor = position;
                let height = self.gpu.as_ref().map_or(1.0, |g| f64::from(g.config.height));
                if let Some(orbit) = self.orbit.as_mut() {
                    if self.right || (self.left.is_some() && self.shift) {
                        orbit.pan(dx, dy, height);
                        self.touched();
                    } else if self.left.is_some() {
                        orbit.turn(dx, dy);
                        self.touched();
                    }
                }
                if self.left.is_some() {
                    self.dragged += dx.abs() + dy.abs();
                }
            }
            WindowEvent::MouseWheel { delta, .. } => {
                let steps = match delta {
                    MouseScrollDelta::LineDelta(_, y) => f64::from(y),
                    MouseScrollDelta::PixelDelta(p) => p.y / 40.0,
                };
                if let Some(orbit) = self.orbit.as_mut() {
                    orbit.zoom(steps);
                    self.touched();
                }
            }
            _ => {}
        }
    }

    fn about_to_wait(&mut self, _: &ActiveEventLoop) {
        if let Some(gpu) = &self.gpu {
            gpu.window.request_redraw();
        }
    }

    fn exiting(&mut self, _: &ActiveEventLoop) {
        let mean = |v: &[f64]| {
            if v.is_empty() {
                0.0
            } else {
                v.iter().sum::<f64>() / v.len() as f64
            }
        };
        let max = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
        self.report.frame_ms = [mean(&self.frame_ms), max(&self.frame_ms)];
        self.report.selected = self
            .selected
            .zip(self.drawn.as_ref())
            .and_then(|(i, d)| d.bodies.get(i))
            .map(|b| b.0.clone());
        self.report.input_to_frame_ms = [mean(&self.input_ms), max(&self.input_ms)];
        if let (Some(path), None) = (&self.options.screenshot, &self.error) {
            let result = match &self.last_frame {
                Some(image) => image.save(path).map_err(|e| e.to_string()),
                None => Err("no frame was presented".to_string()),
            };
            if let Err(message) = result {
                self.error = Some(ViewError::Screenshot {
                    path: path.clone(),
                    message,
                });
            }
        }
    }
}

impl App {
    /// Notes an input: the next frame shows it.
    fn touched(&mut self) {
        let now = Instant::now();
        self.input.get_or_insert(now);
        self.last_input = Some(now);
    }

    /// Selects the body under the cursor (or none).
    fn select(&mut self) {
        let (Some(orbit), Some(drawn), Some(gpu)) = (&self.orbit, &self.drawn, &self.gpu) else {
            return;
        };
        let (origin, direction) = orbit.ray(
            self.cursor.x,
            self.cursor.y,
            f64::from(gpu.config.width),
            f64::from(gpu.config.height),
        );
        let spheres: Vec<(Point3<f64>, f64)> = drawn.bodies.iter().map(|b| b.1).collect();
        self.selected = pick(&origin, &direction, &spheres);
        self.touched();
    }
}

/// The file's modification time, if it can be read.
fn modified(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}

/// Reads `texture` (8-bit, four channels, BGRA where `bgra`) back as RGBA.
fn read_back(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    bgra: bool,
) -> Result<image::RgbaImage, ViewError> {
    let size = texture.size();
    let row = 4 * size.width;
    let padded = row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("soak view read-back"),
        size: u64::from(padded) * u64::from(size.height),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("soak view read-back"),
    });
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: Some(size.height),
            },
        },
        size,
    );
    queue.submit([encoder.finish()]);
    let slice = buffer.slice(..);
    slice.map_async(wgpu::MapMode::Read, |_| {});
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| ViewError::Window(format!("reading the frame back: {e}")))?;
    let data = slice
        .get_mapped_range()
        .map_err(|e| ViewError::Window(format!("reading the frame back: {e}")))?;
    let mut pixels = Vec::with_capacity((row * size.height) as usize);
    for y in 0..size.height as usize {
        let line = &data[y * padded as usize..y * padded as usize + row as usize];
        for p in line.chunks_exact(4) {
            if bgra {
                pixels.extend_from_slice(&[p[2], p[1], p[0], p[3]]);
            } else {
                pixels.extend_from_slice(p);
            }
        }
    }
    drop(data);
    buffer.unmap();
    image::RgbaImage::from_raw(size.width, size.height, pixels)
        .ok_or_else(|| ViewError::Window("the frame read back has the wrong size".into()))
}
