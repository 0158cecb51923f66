//! Each step's work: [`Driver::flood`] (advance the liquid inside
//! flooding bodies and hand its mass to the engine), [`Driver::apply`]
//! (predict each body's pose, evaluate its buoyancy and drag, pass them
//! through the firewall and hand them to the engine), [`Driver::wet`],
//! [`Driver::splash`], [`Driver::step_waves`], and
//! [`Driver::before_step`] and [`Driver::after_step`], which do a whole
//! step around the engine's.

use nalgebra::{Isometry3, Matrix3, Point3, Translation3, UnitQuaternion, Vector3};
use rayon::prelude::*;
use soak_hydro::{
    AddedMass, BodyState, BuoyancyMode, HydroForces, HydroOptions, MassProperties, Water, WaterPlane, Wrench,
};

use crate::body::{SlamReport, SlamState, SoakBody};
use crate::config::{Slamming, SoakId};
use crate::driver::{Driver, Impact};
use crate::engine::{Bodies, BodiesMut, EngineBody, Handle, StepParams};
use crate::error::SoakError;
use crate::implicit::{IMPLICIT_NEGLIGIBLE, implicit_heave, implicit_weight};
use crate::inertial::{EngineMap, Inertial};
use crate::phases::PhaseClock;
use crate::radiation::{entry_weight, sea_excitation, water_motion};
use crate::scratch::{Handed, Prepared};
use crate::waves::{CoupledWaves, Pressed};
use soak_seakeeping::RadiationState;

impl<H: Handle> Driver<H> {
    /// Advances the liquid inside every flooding body by `dt` (s) at the
    /// driver's time, with the body's pose as the engine has it now and the
    /// driver's water (wall exchange, then redistribution; see
    /// [`Flooding::step`](soak_graph::Flooding::step)), and, when the liquid
    /// changed, hands its mass plus any ballast to the engine
    /// ([`Driver::sync_liquid_mass`]). Bodies without flooding are
    /// not visited beyond a check. [`Driver::before_step`] calls it first.
    ///
    /// The liquid's pressure uses the driver's fluid gravity
    /// ([`Driver::set_gravity`]).
    ///
    /// # Errors
    /// A flooding body the engine no longer has, a liquid step that failed
    /// (the body's liquid is then unchanged), invalid mass properties.
    pub fn flood<B: BodiesMut<Handle = H> + ?Sized>(
        &mut self,
        bodies: &mut B,
        dt: f64,
    ) -> Result<(), SoakError> {
        for k in 0..self.bodies.len() {
            let b = &mut self.bodies[k];
            let Some(flooding) = &mut b.effects.flooding else {
                continue;
            };
            let pose = bodies
                .body(b.handle)
                .ok_or_else(|| SoakError::MissingBody { name: b.name.clone() })?
                .pose;
            let report = flooding
                .step(&b.atlas, &pose, &self.water, self.time, dt)
                .map_err(|source| SoakError::Flow {
                    name: b.name.clone(),
                    source,
                })?;
            b.flood.last = report;
            if report.changed() {
                self.sync_liquid_mass(SoakId(k), bodies)?;
            }
        }
        Ok(())
    }

    /// Evaluates every body's buoyancy and drag and hands them to the
    /// engine as the force and torque of its next step (replacing the
    /// previous step's), for the step `step` describes. Does not advance
    /// time, flood ([`Driver::flood`]) nor wet bodies ([`Driver::wet`]);
    /// [`Driver::before_step`] does all of them.
    ///
    /// The engine holds an external force constant over its `s` substeps,
    /// which makes any position-dependent force (a spring, buoyancy) gain
    /// energy every step. Evaluating the force at the pose predicted
    /// `β = (s − 1)/(2s)` of a step ahead makes the step area-preserving
    /// again (exactly so for a linear restoring force), so a floating body
    /// bobs for minutes without its amplitude growing or decaying.
    pub fn apply<B: BodiesMut<Handle = H> + ?Sized>(&mut self, bodies: &mut B, step_params: &StepParams) {
        let mut clock = PhaseClock::start();
        let dt = step_params.dt;
        let substeps = step_params.substeps_f64();
        let lookahead = (substeps - 1.0) / (2.0 * substeps) * dt;
        let t = self.time;
        let step = self.steps;
        // The interactive waves raise the highest crest by theirs.
        let crest = self.waves.as_deref().map_or(0.0, |w| w.solver.highest());
        // A spectral sea the device reads itself: its crest is not bounded
        // here (that would evaluate its whole tile on the CPU as well), and
        // a body above it finds no texel under water on the device.
        let device_sea = self.reads_on_device()
            && self
                .water
                .surface
                .as_any()
                .is_some_and(|s| s.is::<soak_hydro::SpectralSurface>());
        let bounds = if device_sea {
            None
        } else {
            self.water
                .surface
                .height_bounds(t)
                .map(|(lo, hi)| (lo, hi + crest))
        };
        // A body that reads a band of the sea's waves meets that band's
        // crest, which may stand above the whole sea's: each band's highest
        // crest, found once a step.
        let mut band_crests: Vec<(*const (), f64)> = Vec::new();
        // The step's lists, kept by the driver from step to step (emptied
        // at its end): a step allocates none of them once they have grown
        // to the bodies' number.
        let mut s = std::mem::take(&mut self.scratch);

        // 1. Which bodies need texel work, at which predicted state.
        let shared = SharedOptions {
            dt,
            density: self.water.density,
            sea: self.sea,
            sea_velocity: self.sea_velocity,
            sea_band: self.sea_band,
        };
        // `s.work`: each body's index and predicted state; `s.engine`: what
        // the engine said of it, in the same order.
        let mut slamming = false;
        for (k, b) in self.bodies.iter_mut().enumerate() {
            if !b.effects.needs_hydrostatics() {
                continue;
            }
            let Some(rb) = bodies.body(b.handle) else {
                continue;
            };
            let (v, w) = (rb.linear_velocity, rb.angular_velocity);
            let now = rb.pose;
            // Predicted pose: the centre of mass moves with v, the body turns with ω.
            let com = now * b.mass.center_of_mass;
            let rotation = UnitQuaternion::from_scaled_axis(w * lookahead) * now.rotation;
            let translation = (com + v * lookahead).coords - rotation * b.mass.center_of_mass.coords;
            let state = BodyState {
                pose: Isometry3::from_parts(Translation3::from(translation), rotation),
                linear_velocity: v,
                angular_velocity: w,
            };
            // Above the highest crest: no texel work at all. A body stiff
            // for the step (see `implicit_heave`) is skipped only if it
            // cannot reach the water within the step, falling at g.
            let centre = state.pose * b.atlas.origin();
            let radius = b.atlas.bounding_radius();
            let reach =
                if implicit_weight(&self.water, &b.shape, rb.mass, dt, substeps) >= IMPLICIT_NEGLIGIBLE {
                    let c = (substeps + 1.0) / (2.0 * substeps);
                    (1.0 - lookahead / dt) * dt * (-v.y).max(0.0)
                        + c * dt * dt * self.water.gravity * rb.gravity_scale.abs()
                } else {
                    0.0
                };
            // A body that pressed on the waves last step is not skipped:
            // it floats on its own depression taken back out.
            let pressing = self
                .waves
                .as_deref()
                .is_some_and(|w| w.own.get(k).is_some_and(|own| !own.is_empty()));
            // (A sea the device reads has no crest bounded here, its bands'
            // neither.)
            let band = match self.sea_band.wavelength(radius) {
                Ok(Some(wavelength)) if !device_sea => self.water.surface.band_limited(wavelength),
                _ => None,
            };
            let highest = match band {
                Some(band) => {
                    let key = std::ptr::from_ref(band).cast::<()>();
                    let crest = match band_crests.iter().find(|(k, _)| *k == key) {
                        Some(&(_, c)) => Some(c),
                        None => band.height_bounds(t).map(|(_, hi)| {
                            band_crests.push((key, hi + crest));
                            hi + crest
                        }),
                    };
                    bounds.zip(crest).map(|((_, hi), c)| hi.max(c))
                }
                None => bounds.map(|(_, hi)| hi),
            };
            if let Some(highest) = highest
                && centre.y - radius - reach > highest
                && !pressing
            {
                b.dry_skips += 1;
                b.forces = HydroForces {
                    center_of_buoyancy: state.pose * b.mass.center_of_mass,
                    ..HydroForces::default()
                };
                bodies.set_wrench(b.handle, &Wrench::default());
                b.applied = Wrench::default();
                b.added_force = Wrench::default();
                if let (Some(run), Some(model)) = (&mut b.radiation, &b.effects.radiation) {
                    let velocity =
                        RadiationState::local_velocity(model, &model.heading(&now.rotation), &v, &w);
                    run.state.record(model, velocity, t);
                    run.force = Wrench::default();
                }
                if let Some(slam) = &mut b.slam {
                    slam.last_added = Some(0.0);
                    slam.report = SlamReport {
                        peak: slam.report.peak,
                        peak_time: slam.report.peak_time,
                        ..SlamReport::default()
                    };
                }
                continue;
            }
            slamming |= b.slam.is_some();
            s.work.push((k, state));
            s.engine.push(rb);
        }

        // The sea, sampled once per body over its footprint, read by the
        // evaluation and by the implicit heave's evaluations at shifted
        // heights (`None`: a plane, or the exact read). A body whose
        // sampling fails (a state that is not finite) is evaluated on the
        // water itself, which reports the error.
        // With interactive waves, a body over their region presses its
        // columns under the base water on them (the pressure a body puts on
        // the waves does not depend on the waves), and floats on the water
        // with the waves on it less that depression, sampled on the waves'
        // cells.
        // A surface that evaluates something for every reader at `t` (a
        // spectral sea's tile) does it once, with every thread, before the
        // bodies read it in parallel; where the device reads it, the CPU
        // does not (a step that falls back to the CPU evaluates it on its
        // first read).
        clock.mark();
        if !s.work.is_empty() && !self.reads_on_device() {
            self.water.surface.prepare(t);
        }
        // Each body's options are made here, once a step, from what every
        // body shares and its own effects.
        {
            let (bodies, water, waves) = (&self.bodies, &self.water, self.waves.as_deref());
            s.work
                .par_iter()
                .map(|(k, state)| {
                    let b = &bodies[*k];
                    let options = shared.of(b, state);
                    let sea = soak_hydro::sampled_water(&b.atlas, water, state, t, &options)
                        .ok()
                        .flatten();
                    let Some(w) = waves else {
                        return Prepared {
                            options,
                            sea,
                            pressed: None,
                        };
                    };
                    let base = sea.as_ref().unwrap_or(water);
                    // A body with radiation makes its waves in its memory.
                    let buoyant = !matches!(b.effects.buoyancy, None | Some(BuoyancyMode::Off))
                        && b.effects.radiation.is_none();
                    let own = if buoyant {
                        w.solver.pressed(&b.atlas, base, state, t).unwrap_or_default()
                    } else {
                        Vec::new()
                    };
                    let with_velocity = options.drag.is_some();
                    let (sea, pressed) =
                        match w.solver.water_for(base, &b.atlas, state, &own, t, with_velocity) {
                            Ok(Some(on)) => (Some(on), Some(own)),
                            _ => (sea, None),
                        };
                    Prepared {
                        options,
                        sea,
                        pressed,
                    }
                })
                .collect_into_vec(&mut s.prepared);
        }

        clock.mark();
        // 2. Evaluate: one GPU batch, or every body in one parallel pass on
        // the CPU (each body's sums in a fixed order: the same results for
        // any number of threads).
        #[cfg(feature = "gpu")]
        if let Some(gpu) = &self.gpu {
            match gpu.evaluate(&self.bodies, &self.water, &s.work, &s.prepared, t) {
                Ok(forces) => s.results.extend(forces.into_iter().map(Ok)),
                Err(e) => {
                    // Keep going on the CPU for this step; say so once per failure.
                    self.firewall.reject(
                        step,
                        "(all)",
                        "gpu evaluation",
                        format!("{e}; evaluated on the CPU"),
                    );
                }
            }
        }
        if s.results.is_empty() {
            let (bodies, water) = (&self.bodies, &self.water);
            s.work
                .par_iter()
                .zip(&s.prepared)
                .map(|((k, state), p)| {
                    let b = &bodies[*k];
                    let options = &p.options;
                    let water = p.sea.as_ref().unwrap_or(water);
                    let r = match (&b.tiled, &b.effects.drag_texels) {
                        (Some(tiled), None) => tiled.evaluate(&b.atlas, water, state, &b.mass, t, options),
                        (Some(tiled), Some(drag)) => {
                            tiled.evaluate_with_drag(&b.atlas, drag, water, state, &b.mass, t, options)
                        }
                        (None, None) => soak_hydro::evaluate(&b.atlas, water, state, &b.mass, t, options),
                        (None, Some(drag)) => {
                            soak_hydro::evaluate_with_drag(&b.atlas, drag, water, state, &b.mass, t, options)
                        }
                    };
                    r.map_err(|e| e.to_string())
                })
                .collect_into_vec(&mut s.results);
        }

        // The water-planes of the slamming bodies (one more pass over their
        // texels; nothing at all in a scene without slamming).
        let planes: Vec<Option<WaterPlane>> = if slamming {
            let (bodies, water) = (&self.bodies, &self.water);
            s.work
                .par_iter()
                .zip(&s.prepared)
                .map(|((k, state), p)| {
                    let b = &bodies[*k];
                    b.slam.as_ref()?;
                    soak_hydro::water_plane(&b.atlas, p.sea.as_ref().unwrap_or(water), state, t).ok()
                })
                .collect()
        } else {
            Vec::new()
        };

        // A body whose evaluation failed presses nothing.
        if let Some(w) = self.waves.as_deref_mut() {
            let pressed = s
                .prepared
                .iter_mut()
                .zip(&s.results)
                .map(|(p, r)| p.pressed.take().filter(|_| r.is_ok()))
                .collect();
            press_waves(w, self.bodies.len(), &s.work, pressed);
        }

        clock.mark();
        // 3. What each body hands the engine: radiation's memory and wrench,
        // the inertia the step moves, slamming, the firewall's checks and
        // the implicit heave, for every body on its own in one parallel
        // pass (each body's in a fixed order: the same for any number of
        // threads). `work` lists the bodies in order, as does the pass.
        s.slot.clear();
        s.slot.resize(self.bodies.len(), usize::MAX);
        for (i, (k, _)) in s.work.iter().enumerate() {
            s.slot[*k] = i;
        }
        {
            let water = &self.water;
            let (results, prepared, engine, planes, work, slot) =
                (&s.results, &s.prepared, &s.engine, &planes, &s.work, &s.slot);
            self.bodies
                .par_iter_mut()
                .enumerate()
                // A body's part is a fraction of a microsecond without
                // radiation, about one with it: a few bodies per task.
                .with_min_len(16)
                .map(|(k, b)| {
                    let i = slot[k];
                    if i == usize::MAX {
                        return None;
                    }
                    let state = &work[i].1;
                    let Prepared { options, sea, .. } = &prepared[i];
                    let sea = sea.as_ref().unwrap_or(water);
                    let plane = planes.get(i).copied().flatten();
                    let rejected = hand(
                        b,
                        &engine[i],
                        state,
                        options,
                        &results[i],
                        sea,
                        plane,
                        water,
                        t,
                        substeps,
                    );
                    Some(Handed {
                        handle: b.handle,
                        applied: b.applied,
                        rejected,
                    })
                })
                .collect_into_vec(&mut s.handed);
        }

        clock.mark();
        // 4. The firewall, then the engine, one body at a time.
        for (k, h) in s.handed.drain(..).enumerate() {
            let Some(h) = h else {
                continue;
            };
            for (quantity, reason) in h.rejected {
                self.firewall.reject(step, &self.bodies[k].name, quantity, reason);
            }
            bodies.set_wrench(h.handle, &h.applied);
        }
        s.clear();
        self.scratch = s;
        clock.mark();
        self.phases = clock.phases();
    }

    /// Advances the liquid texture of every wet body by `dt` (s) at the
    /// driver's time, with the body's pose as the engine has it now and the
    /// driver's water and environment: absorption through the submerged
    /// texels, evaporation from the others, then the body's own diffusion
    /// (see [`Wetting::step`](soak_wet::Wetting::step)). Bodies without wetting
    /// are not visited beyond a check. [`Driver::before_step`] calls it.
    ///
    /// A body whose pose is not finite is skipped and the firewall records
    /// it; invalid wetting settings are an error.
    pub fn wet<B: Bodies<Handle = H> + ?Sized>(&mut self, bodies: &B, dt: f64) -> Result<(), SoakError> {
        let (t, step) = (self.time, self.steps);
        for b in &mut self.bodies {
            let Some(wetting) = &mut b.effects.wetting else {
                continue;
            };
            let Some(rb) = bodies.body(b.handle) else {
                continue;
            };
            let pose = rb.pose;
            let finite = pose.translation.vector.iter().all(|c| c.is_finite())
                && pose.rotation.coords.iter().all(|c| c.is_finite());
            if !finite {
                self.firewall
                    .reject(step, &b.name, "wetting pose", format!("non-finite {pose:?}"));
                continue;
            }
            b.wet_report = wetting
                .step(&b.atlas, &pose, &self.water, &self.environment, t, dt)
                .map_err(|source| SoakError::Wet {
                    name: b.name.clone(),
                    source,
                })?;
        }
        Ok(())
    }

    /// Drops `splash` on every wet body, each at its pose as the engine has
    /// it now; returns the volume that stuck (m³, summed over the bodies;
    /// the rest ran off saturated texels or landed on no body). Bodies
    /// without wetting are not touched.
    ///
    /// # Errors
    /// An invalid splash, or a wet body whose pose is not finite.
    pub fn splash<B: Bodies<Handle = H> + ?Sized>(
        &mut self,
        bodies: &B,
        splash: &soak_wet::Splash,
    ) -> Result<f64, SoakError> {
        let mut stuck = 0.0;
        for b in &mut self.bodies {
            let (Some(wetting), Some(rb)) = (&mut b.effects.wetting, bodies.body(b.handle)) else {
                continue;
            };
            stuck += wetting
                .splash(&b.atlas, &rb.pose, splash)
                .map_err(|source| SoakError::Wet {
                    name: b.name.clone(),
                    source,
                })?;
        }
        Ok(stuck)
    }

    /// Advances the interactive waves (if the driver has them, see
    /// [`Driver::with_waves`]) by `dt` (s) under the pressure the
    /// bodies put on them at [`Driver::apply`], then moves their
    /// region to follow the bodies. [`Driver::before_step`] calls it
    /// after `apply`. Nothing without waves.
    ///
    /// # Errors
    /// [`SoakError::Waves`] for a `dt` that is not finite and > 0 (the
    /// waves are then unchanged).
    pub fn step_waves(&mut self, dt: f64) -> Result<(), SoakError> {
        let Some(w) = self.waves.as_deref_mut() else {
            return Ok(());
        };
        w.step(dt)?;
        w.follow()
    }

    /// Advances the driver's clock (for moving waves) by `dt` seconds and
    /// counts the step. [`Driver::after_step`] does it.
    pub fn advance(&mut self, dt: f64) {
        self.time += dt;
        self.steps += 1;
    }

    /// Sets the fluid's hydrostatic gravity, m/s² (the length of the
    /// engine's gravity vector: keep the two the same, as the adapters do
    /// every step).
    pub fn set_gravity(&mut self, gravity: f64) {
        self.water.gravity = gravity;
    }

    /// Everything the driver does before the engine steps: advances the
    /// liquid inside flooding bodies ([`Driver::flood`]), hands the engine
    /// the fluid forces ([`Driver::apply`]), wets the wet bodies over the
    /// step ([`Driver::wet`]) and steps the interactive waves
    /// ([`Driver::step_waves`]). Then step the engine once by `step.dt`,
    /// and call [`Driver::after_step`].
    ///
    /// # Errors
    /// A flooding, wetting or waves step that failed (see
    /// [`Driver::flood`], [`Driver::wet`] and [`Driver::step_waves`]):
    /// do not step the engine then.
    pub fn before_step<B: BodiesMut<Handle = H> + ?Sized>(
        &mut self,
        bodies: &mut B,
        step: &StepParams,
    ) -> Result<(), SoakError> {
        self.flood(bodies, step.dt)?;
        self.apply(bodies, step);
        self.wet(bodies, step.dt)?;
        self.step_waves(step.dt)
    }

    /// What the driver does once the engine has stepped by `dt` (s):
    /// advances its clock ([`Driver::advance`]). An engine whose contacts
    /// can tear holes calls [`Driver::tear`] after it.
    pub fn after_step(&mut self, dt: f64) {
        self.advance(dt);
    }

    /// Opens the holes the engine's last step's hard contacts call for
    /// ([`ImpactHoles`](crate::ImpactHoles)), recording them in
    /// [`Driver::impacts`]. `contacts(handle)` lists the contact pairs of
    /// the body `handle` names after the step: each pair's impulse over
    /// the step (N·s) and its deepest contact point (world, m), in the
    /// engine's order. Only bodies with an impact rule are asked; a pair
    /// whose impulse is not above the rule's threshold is passed over.
    ///
    /// # Errors
    /// A body with an impact rule the engine no longer has.
    pub fn tear<B: Bodies<Handle = H> + ?Sized>(
        &mut self,
        bodies: &B,
        mut contacts: impl FnMut(H) -> Vec<(f64, Point3<f64>)>,
    ) -> Result<(), SoakError> {
        self.impacts.clear();
        for k in 0..self.bodies.len() {
            let b = &self.bodies[k];
            let Some(rule) = b.effects.impact_holes else {
                continue;
            };
            let body_pose = bodies
                .body(b.handle)
                .ok_or_else(|| SoakError::MissingBody { name: b.name.clone() })?
                .pose;
            let blows: Vec<(Point3<f64>, f64)> = contacts(b.handle)
                .into_iter()
                .filter(|(impulse, _)| !impulse.is_nan() && *impulse > rule.impulse)
                .map(|(impulse, point)| (body_pose.inverse_transform_point(&point), impulse))
                .collect();
            for (centre, impulse) in blows {
                let texels = self.open_hole(SoakId(k), centre, rule.radius)?;
                self.impacts.push(Impact {
                    body: SoakId(k),
                    time: self.time,
                    centre: [centre.x, centre.y, centre.z],
                    impulse,
                    texels,
                });
            }
        }
        Ok(())
    }
}

/// One step's slamming of a body whose water-plane is `plane` at `state`
/// (see [`Slamming`]): updates its state and report, returns the wrench
/// (world, about the centre of mass). `end` is the time at the end of the
/// step, for the peak.
#[allow(clippy::too_many_arguments)]
fn slam_step(
    slam: &mut SlamState,
    rule: &Slamming,
    plane: &WaterPlane,
    state: &BodyState,
    mass: &MassProperties,
    inertial: &Inertial,
    density: f64,
    dt: f64,
    end: f64,
) -> Wrench {
    let added = plane.plate_added_mass(density);
    let last = slam.last_added.unwrap_or(added);
    slam.last_added = Some(added);
    let rate = (added - last) / dt;
    let point = Point3::new(plane.centroid.x, plane.height, plane.centroid.y);
    let com = state.pose * mass.center_of_mass;
    let speed = -(state.linear_velocity + state.angular_velocity.cross(&(point - com))).y;
    let mut force = 0.0;
    let mut capped = false;
    if rate > 0.0 && speed > 0.0 && rate.is_finite() && speed.is_finite() {
        force = rate * speed;
        // At most `cap` of the downward momentum in one step.
        let cap = rule.cap * inertial.vertical() * speed / dt;
        if force > cap {
            force = cap;
            capped = true;
        }
    }
    let f = Vector3::new(0.0, force, 0.0);
    let (peak, peak_time) = if force > slam.report.peak {
        (force, end)
    } else {
        (slam.report.peak, slam.report.peak_time)
    };
    slam.report = SlamReport {
        force: f,
        point,
        added_mass: added,
        rate,
        speed,
        capped,
        peak,
        peak_time,
    };
    Wrench {
        force: f,
        torque: (point - com).cross(&f),
    }
}

/// Puts this step's presses on the waves: the pressure is what the bodies
/// in `work` pressed now (`pressed`, in `work`'s order; `None` for a body
/// that pressed nothing), every other body's depression is cleared, the
/// first press is held at rest when asked, and the region's next centre is
/// the middle of the bodies that pressed.
fn press_waves(
    w: &mut CoupledWaves,
    bodies: usize,
    work: &[(usize, BodyState)],
    pressed: Vec<Option<Pressed>>,
) {
    w.own.resize_with(bodies, Vec::new);
    w.own.iter_mut().for_each(Vec::clear);
    w.solver.clear_pressure();
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for ((k, state), cells) in work.iter().zip(pressed) {
        let Some(cells) = cells.filter(|c| !c.is_empty()) else {
            continue;
        };
        w.solver.add_pressure(&cells);
        if w.settle_pending {
            w.solver.hold(&cells);
            w.moved = true;
        }
        let p = state.pose.translation.vector;
        lo = [lo[0].min(p.x), lo[1].min(p.z)];
        hi = [hi[0].max(p.x), hi[1].max(p.z)];
        w.own[*k] = cells;
    }
    w.settle_pending = false;
    w.follow = (lo[0] <= hi[0]).then(|| [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])]);
}

/// What a body's water adds to its step: the inertia the step moves and
/// radiation's wrench (with the reason the firewall must record when that
/// wrench came out non-finite and was set to nil). Each body's is its own
/// (radiation's memory records the body's velocity here): [`hand`] makes
/// them for every body at once, in parallel.
struct Moved {
    inertial: Inertial,
    /// What handing the engine the body's wrench takes of its turn (with
    /// an added mass; see [`Inertial::for_engine`]).
    engine: Option<EngineMap>,
    radiation: Wrench,
    rejected: Option<String>,
}

/// What body `b` hands the engine for the step `options.dt` (s) at time
/// `t` (s), from `result`, what its texels gave at its predicted `state`
/// (`rb` what the engine says of it, `sea` the water it was evaluated on,
/// `water` the driver's, `plane` its water-plane where it slams): the
/// wrench it keeps as [`SoakBody::applied`], with the added force, the
/// forces and its radiation's and slamming's states. A quantity the
/// firewall rejects keeps its last good value; what it rejected comes back,
/// in order, with the reasons. A failed evaluation keeps the last wrench.
#[allow(clippy::too_many_arguments)]
fn hand<H>(
    b: &mut SoakBody<H>,
    rb: &EngineBody,
    state: &BodyState,
    options: &HydroOptions,
    result: &Result<HydroForces, String>,
    sea: &Water,
    plane: Option<WaterPlane>,
    water: &Water,
    t: f64,
    substeps: f64,
) -> Vec<(&'static str, String)> {
    let dt = options.dt;
    let mut rejected = Vec::new();
    let forces = match result {
        Ok(f) => f,
        Err(e) => {
            rejected.push(("body state", e.clone()));
            return rejected;
        }
    };
    let Moved {
        inertial,
        engine,
        radiation,
        rejected: reason,
    } = moved(b, rb, state, forces, water, t, dt);
    if let Some(reason) = reason {
        rejected.push(("radiation", reason));
    }
    // Slamming: the momentum the water-plane's growing added mass takes,
    // acting over the step like the drag.
    let slam = match (b.slam.as_deref_mut(), b.effects.slamming, plane) {
        (Some(slam), Some(rule), Some(plane)) => slam_step(
            slam,
            &rule,
            &plane,
            state,
            &b.mass,
            &inertial,
            water.density,
            dt,
            t + dt,
        ),
        _ => Wrench::default(),
    };
    let mut wrench = Wrench::default();
    // Buoyancy can never exceed the weight of fluid the whole body displaces.
    let limit = 1.5 * water.density * water.gravity * b.shape.volume + 1e-9;
    let bw = forces.buoyancy;
    if !bw.is_finite() {
        rejected.push(("buoyancy", format!("non-finite {bw:?}")));
        wrench = wrench + last_part(&b.forces.buoyancy);
    } else if bw.force.norm() > limit {
        rejected.push((
            "buoyancy",
            format!("|F| = {:.3e} N exceeds {:.3e} N", bw.force.norm(), limit),
        ));
        wrench = wrench + last_part(&b.forces.buoyancy);
    } else {
        // The drag (and slamming) is applied with the buoyancy: the
        // implicit solve counts it.
        let drag = last_part(&forces.drag) + slam + radiation;
        wrench = wrench
            + implicit_heave(
                b, rb, sea, state, options, t, substeps, limit, bw, drag, &inertial,
            );
    }
    wrench = wrench + slam + radiation;
    if forces.drag.is_finite() {
        wrench = wrench + forces.drag;
    } else {
        rejected.push(("drag", format!("non-finite {:?}", forces.drag)));
    }
    // With an added mass: the wrench that gives the body alone the
    // accelerations the body and the water would take.
    let applied = match &engine {
        Some(map) => {
            let g = water.gravity * rb.gravity_scale;
            let engine = inertial.for_engine(map, &wrench, &b.mass.inertia, g);
            if engine.is_finite() { engine } else { wrench }
        }
        None => wrench,
    };
    b.added_force = Wrench {
        force: applied.force - wrench.force,
        torque: applied.torque - wrench.torque,
    };
    b.applied = applied;
    b.forces = *forces;
    rejected
}

/// Body `b`'s [`Moved`] for the step `dt` (s) at time `t` (s): `rb` is what
/// the engine says of it, `state` its predicted state and `forces` what its
/// texels gave at that state, on `water`.
fn moved<H>(
    b: &mut SoakBody<H>,
    rb: &EngineBody,
    state: &BodyState,
    forces: &HydroForces,
    water: &Water,
    t: f64,
    dt: f64,
) -> Moved {
    // What the step moves: the body, and with an added mass the
    // water it sets moving (as much of it as is under water now).
    // Radiation's A∞ supersedes the added mass; its memory acts
    // with the drag.
    let mut radiation = Wrench::default();
    let mut rejected = None;
    let inertial = match (&b.effects.radiation, &mut b.radiation, &b.effects.added_mass) {
        // Radiation where the step resolves the body's motion (see
        // `RadiationModel::resolved_by`); otherwise as without it.
        (Some(model), Some(run), _) if model.resolved_by(dt) => {
            // Whole from half the rest displacement up (small
            // motions see the linear model unchanged), fading to
            // none as the body leaves the water.
            let rest = model.hydrostatics().volume;
            let share = (2.0 * forces.submerged_volume / rest).clamp(0.0, 1.0);
            // The share at the last step (none before the first).
            let last_share = run
                .state
                .has_history()
                .then(|| (2.0 * b.forces.submerged_volume / rest).clamp(0.0, 1.0));
            // Read in the model's frame: the body's heading.
            let rotation = &model.heading(&rb.pose.rotation);
            // On a sea of known waves the body radiates as it
            // moves and takes linear theory's excitation: the
            // texels' hydrostatic columns and what the model adds
            // to them (the pressure's decay with depth and the
            // diffraction). On other moving water it radiates
            // against the water's own vertical motion at the
            // centre of buoyancy (relative velocity and
            // acceleration: the long-wave limit of the
            // diffraction). The horizontal motion is left to the
            // texels' forces: a body does not ride the orbital
            // velocity it samples at its own place, whose mean is
            // no drift of the real sea's.
            let center = rb.pose * b.mass.center_of_mass;
            let pushed = b.effects.buoyancy == Some(BuoyancyMode::Pressure);
            let excitation = sea_excitation(water, model, rotation, &center, t, pushed);
            let (flow, flow_acceleration) = if excitation.is_some() {
                (Vector3::zeros(), Vector3::zeros())
            } else {
                let (u, a) = water_motion(water, &forces.center_of_buoyancy, t, dt);
                (Vector3::y() * u.y, Vector3::y() * a.y)
            };
            let velocity = RadiationState::local_velocity(
                model,
                rotation,
                &(rb.linear_velocity - flow),
                &rb.angular_velocity,
            );
            run.state.record(model, velocity, t);
            // Held over the step: the memory's force at its middle.
            let (force, torque) = run.state.world_force_ahead(model, rotation, 0.5 * dt);
            let (linear, angular) = model.infinite_blocks(&model.heading(&state.pose.rotation));
            let excitation = excitation.unwrap_or_default();
            // Entering the water: the share of A∞ that grows over
            // the step takes its momentum, `−w ΔA v / dt` (and
            // `−w ΔA ω / dt` turning), so that a light body and
            // its water keep the momentum the body brought: held
            // at its speed against the water's whole inertia, a
            // body a hundred times lighter than the water it moves
            // came out with more energy than it went in with. The
            // weight `w = (a / (m + a))³` is the water's part of
            // the inertia (`a` the mean diagonal of A∞, `m` the
            // body's mass or mean principal inertia), cubed: whole
            // for such a body, negligible for one as heavy as its
            // water or heavier, which bobs through the surface on
            // a swell as linear theory (a constant A∞, no entry)
            // says. Leaving the water, the water keeps what it
            // took. With slamming on, the slam takes the entry.
            let growth = last_share.map_or(0.0, |last| share - last);
            let entry = if growth > 0.0 && b.effects.slamming.is_none() {
                let r = state.pose.rotation.to_rotation_matrix().into_inner();
                let w_linear = entry_weight(linear.trace() / 3.0, rb.mass);
                let w_angular = entry_weight(angular.trace() / 3.0, b.mass.inertia.trace() / 3.0);
                Wrench {
                    force: -(linear * (w_linear * growth)) * (rb.linear_velocity - flow) / dt,
                    torque: -(r * (angular * (w_angular * growth)) * r.transpose()) * rb.angular_velocity
                        / dt,
                }
            } else {
                Wrench::default()
            };
            radiation = Wrench {
                force: (force + linear * flow_acceleration + excitation.force) * share + entry.force,
                torque: (torque + excitation.torque) * share + entry.torque,
            };
            if !radiation.is_finite() {
                rejected = Some(format!("non-finite {radiation:?}"));
                radiation = Wrench::default();
            }
            run.force = radiation;
            if share > 0.0 {
                Inertial::with_blocks(rb.mass, &b.mass.inertia, &(linear * share), &(angular * share))
            } else {
                Inertial::plain(rb.mass, &b.mass.inertia)
            }
        }
        (_, _, None) => Inertial::plain(rb.mass, &b.mass.inertia),
        (_, _, Some(added)) => Inertial::with_added(
            rb.mass,
            &b.mass.inertia,
            added,
            &state.pose.rotation,
            water.density,
            forces.submerged_volume,
        ),
    };
    let engine = inertial.engine_map(
        &b.mass.inertia,
        &state.pose.rotation,
        rb.gyroscopic.then_some(&rb.angular_velocity),
    );
    Moved {
        inertial,
        engine,
        radiation,
        rejected,
    }
}

/// What every body's [`HydroOptions`] share in a step.
#[derive(Clone, Copy)]
struct SharedOptions {
    dt: f64,
    /// The water's density, kg/m³.
    density: f64,
    sea: soak_hydro::SeaSampling,
    sea_velocity: soak_hydro::SeaVelocity,
    sea_band: soak_hydro::SeaBand,
}

impl SharedOptions {
    /// Body `b`'s options at `state`: its buoyancy mode, drag and the
    /// added mass its implicit drag moves with it (none for a body without
    /// drag, whose evaluation would not read it).
    fn of<H>(&self, b: &SoakBody<H>, state: &BodyState) -> HydroOptions {
        let dragged = b.effects.drag.is_some() || b.effects.drag_texels.is_some();
        HydroOptions {
            buoyancy: b.effects.buoyancy.unwrap_or(BuoyancyMode::Off),
            drag: b.effects.drag,
            dt: self.dt,
            sea: b.effects.sea.unwrap_or(self.sea),
            sea_velocity: self.sea_velocity,
            sea_band: self.sea_band,
            added_mass: dragged
                .then(|| self.added_mass(b, &state.pose.rotation))
                .flatten(),
        }
    }

    /// The added mass body `b`'s implicit drag moves with it, turned by
    /// `rotation`: with radiation where the step resolves it, radiation's
    /// translational A∞ as the step takes it (whole from half the rest
    /// displacement under water, a share of it below), so that the drag
    /// does not ask more of the body's few submerged texels than the body
    /// and its water could give (a light torus' drag, solved on its own
    /// mass, sent it off at 40 m/s); its turning with the body's own
    /// inertia (the rotational A∞, read about the body's axes at rest, is
    /// the inertia of no rigid body: a rod's about its length is nil,
    /// about its breadth several times its own, and a drag solve through
    /// it traded the water's turning into the rod's spin about its
    /// length). Otherwise its added-mass effect, if any.
    fn added_mass<H>(&self, b: &SoakBody<H>, rotation: &UnitQuaternion<f64>) -> Option<AddedMass> {
        match &b.effects.radiation {
            Some(model) if b.radiation.is_some() && model.resolved_by(self.dt) && self.density > 0.0 => {
                let (linear, _) = model.infinite_blocks(&model.heading(rotation));
                let r = rotation.to_rotation_matrix().into_inner();
                Some(AddedMass {
                    translation: r.transpose() * linear * r / self.density,
                    rotation: Matrix3::zeros(),
                    volume: 0.5 * model.hydrostatics().volume,
                })
            }
            _ => b.effects.added_mass.as_deref().copied(),
        }
    }
}

fn last_part(w: &Wrench) -> Wrench {
    if w.is_finite() { *w } else { Wrench::default() }
}
