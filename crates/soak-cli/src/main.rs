//! `soak`: bake meshes, measure hydrostatics and accuracy, run scenes.
//!
//! The command a user runs from a terminal; every number it prints comes
//! from the library crates (`soak_bake`, `soak_hydro`, `soak_rapier`,
//! `soak_report`, …), which it only calls and formats. Its families:
//!
//! - `soak demo`: the thesis' Chapter 7 cases side by side, with plots,
//!   CSV and rendered stills;
//! - `soak bake MESH`, `soak hydro MESH`: a mesh's atlas and its
//!   hydrostatics at a pose beside the exact references;
//! - `soak accuracy`, `soak stress`, `soak bench`: the accuracy report
//!   (the thesis' Fig. 7.10 extended), the stability matrix and the
//!   scaling bench;
//! - `soak simulate SCENE.toml`, `soak render SCENE.toml`, `soak view
//!   SCENE.toml`: scene files run headless, rendered, and shown live;
//! - `soak sea SCENE.toml`: a scene's spectral sea against the spectrum it
//!   asks for;
//! - `soak segment MESH`, `soak sweep`: a hull's liquid graph, and the wet
//!   shading's material sweep.
//!
//! `soak --help` lists every command; `soak COMMAND --help` its options.

mod accuracy;
mod bake;
mod bench;
mod common;
mod demo;
mod hydro;
mod interrupt;
mod progress;
mod render;
mod sea;
mod seakeeping;
mod segment;
mod simulate;
mod stills;
mod stress;
mod sweep;
mod view;

use clap::{Parser, Subcommand};

/// Textured meshes that float, take on water, sink, get wet and dry.
#[derive(Parser)]
#[command(name = "soak", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run the embedded demo: the thesis' Chapter 7 cases, with plots.
    Demo(demo::Args),
    /// Bake a mesh into a texel atlas and print its summary.
    Bake(bake::Args),
    /// Mass properties and hydrostatics of a mesh at a pose, against the exact reference.
    Hydro(hydro::Args),
    /// Run a scene file headless; print final states, write time series.
    Simulate(simulate::Args),
    /// What each digit of accuracy costs in time: errors and times per path and resolution.
    Accuracy(accuracy::Args),
    /// Segment a closed mesh into its liquid graph: print nodes and edges, draw them on the mesh.
    Segment(segment::Args),
    /// Step time of a Rapier world against the number of floating bodies: a table and a log–log plot.
    Bench(bench::Args),
    /// A scene's spectral sea as realised against its target spectrum: Hs, peak period, the spectrum (a table and a plot), a still.
    Sea(sea::Args),
    /// A mesh floating at rest: radiation coefficients, RAOs and free decay against frequency (a table and plots).
    Seakeeping(seakeeping::Args),
    /// Stability matrix: meshes × densities × time steps × scales × waters × effects; non-zero exit on a failing cell.
    Stress(stress::Args),
    /// Render frames of a scene file (PNG): wet surfaces, water, debug views, force arrows.
    Render(render::Args),
    /// Render the material sweep of the thesis' Fig. 6.3: materials × liquids, dry to saturated.
    Sweep(sweep::Args),
    /// Show a scene file live in a window: orbit camera, play/pause, views, overlay, picking, reload on save.
    View(view::Args),
}

fn main() -> std::process::ExitCode {
    match run(Cli::parse()) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => match e.downcast_ref::<interrupt::Interrupted>() {
            Some(stopped) => {
                eprintln!("{stopped}");
                std::process::ExitCode::from(interrupt::EXIT_CODE)
            }
            None => {
                eprintln!("error: {}", message(&e));
                std::process::ExitCode::FAILURE
            }
        },
    }
}

/// The error and its causes, each said once: a cause that its error's own
/// message already quotes (`cannot read `x.obj`: No such file or
/// directory`) is not repeated after it.
fn message(e: &anyhow::Error) -> String {
    let mut text = e.to_string();
    for cause in e.chain().skip(1) {
        let cause = cause.to_string();
        if !text.contains(&cause) {
            text.push_str(": ");
            text.push_str(&cause);
        }
    }
    text
}

fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Demo(args) => demo::run(&args),
        Command::Bake(args) => bake::run(&args),
        Command::Hydro(args) => hydro::run(&args),
        Command::Simulate(args) => simulate::run(&args),
        Command::Accuracy(args) => accuracy::run(&args),
        Command::Segment(args) => segment::run(&args),
        Command::Sea(args) => sea::run(&args),
        Command::Seakeeping(args) => seakeeping::run(&args),
        Command::Stress(args) => stress::run(&args),
        Command::Bench(args) => bench::run(&args),
        Command::Render(args) => render::run(&args),
        Command::Sweep(args) => sweep::run(&args),
        Command::View(args) => view::run(&args),
    }
}
