//! `soak segment MESH`: the automatic liquid graph of a closed mesh.
//!
//! Segments the mesh by its Shape Diameter Function
//! (`soak_graph::segment`), turns the segments into a liquid graph
//! (`LiquidGraph::from_segmentation`), prints its nodes (position,
//! capacity) and pipes, and writes a picture: three orthographic views
//! (front, side, top) of the mesh, flat-shaded in one colour per segment,
//! with the graph drawn over it — a disc per node (area ∝ capacity^⅔,
//! labelled with its index) and a line per pipe.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Context;
use image::{Rgb, RgbImage};
use nalgebra::{Point3, Vector3};
use serde::Serialize;
use soak_bake::Mesh;
use soak_graph::segment::{SegmentOptions, Segmentation, segment};
use soak_graph::{LiquidGraph, SegmentGraphOptions};
use soak_report::chart::palette;

use crate::common;

/// Arguments of `soak segment`.
#[derive(clap::Args)]
pub struct Args {
    /// A closed mesh file (.obj, .gltf, .glb) or a builtin name (builtin:dumbbell, builtin:boat, ...).
    mesh: String,
    /// Number of SDF clusters (Gaussian components).
    #[arg(long, short = 'k', default_value_t = 5)]
    clusters: usize,
    /// Seed of the ray jitter and k-means++.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Fraction of each segment's volume open to liquid, in [0, 1].
    #[arg(long, default_value_t = 1.0)]
    porosity: f64,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
    /// Where to write the picture (PNG); default out/segment/NAME.png.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write the graph as a graph file too (.toml or .json), for scenes and editing.
    #[arg(long)]
    graph: Option<PathBuf>,
    /// Side of each of the three views, pixels.
    #[arg(long, default_value_t = 480)]
    size: u32,
}

#[derive(Serialize)]
struct NodeOut {
    index: usize,
    /// Object space, m.
    position: [f64; 3],
    /// m³.
    capacity: f64,
    /// Fitted sphere radius, m.
    radius: f64,
    faces: usize,
    /// m².
    area: f64,
    cluster: u32,
    fit: String,
}

#[derive(Serialize)]
struct EdgeOut {
    a: usize,
    b: usize,
    /// Shared boundary, m.
    boundary: f64,
    /// Pipe radius, m.
    radius: f64,
    /// Pipe length, m.
    length: f64,
}

#[derive(Serialize)]
struct Report {
    mesh: String,
    triangles: usize,
    /// m³.
    volume: f64,
    clusters: usize,
    nodes: Vec<NodeOut>,
    edges: Vec<EdgeOut>,
    /// Wall-clock time of segmentation stages, ms.
    timings_ms: Timings,
    picture: String,
}

#[derive(Serialize)]
struct Timings {
    topology: f64,
    sdf: f64,
    clustering: f64,
    graph_cut: f64,
    nodes: f64,
    total: f64,
}

pub fn run(args: &Args) -> anyhow::Result<()> {
    let mesh = common::mesh(&args.mesh, false)?;
    let options = SegmentOptions {
        clusters: args.clusters,
        seed: args.seed,
        ..SegmentOptions::default()
    };
    let start = Instant::now();
    let seg = segment(&mesh, &options).with_context(|| format!("segmenting {}", mesh.name))?;
    let segment_ms = common::ms(start);
    let graph = LiquidGraph::from_segmentation(
        &seg,
        &SegmentGraphOptions {
            porosity: args.porosity,
            ..SegmentGraphOptions::default()
        },
    )?;
    let out = args.out.clone().unwrap_or_else(|| {
        let stem: String = mesh
            .name
            .rsplit(['/', '\\'])
            .next()
            .unwrap_or("mesh")
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '.' || c == '-' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        PathBuf::from("out/segment").join(format!("{stem}.png"))
    });
    draw(&mesh, &seg, &graph, args.size.clamp(64, 4096))?.write(&out)?;
    if let Some(path) = &args.graph {
        let text = match path.extension().and_then(|e| e.to_str()) {
            Some("json") => soak_graph::to_json(&graph),
            _ => soak_graph::to_toml(&graph),
        };
        std::fs::write(path, text).with_context(|| format!("writing {}", path.display()))?;
    }
    let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
    let report = Report {
        mesh: mesh.name.clone(),
        triangles: mesh.triangles.len(),
        volume: mesh.volume(),
        clusters: args.clusters,
        nodes: graph
            .nodes()
            .zip(&seg.segments)
            .enumerate()
            .map(|(i, (n, s))| NodeOut {
                index: i,
                position: [n.position.x, n.position.y, n.position.z],
                capacity: n.capacity,
                radius: s.radius,
                faces: s.faces,
                area: s.area,
                cluster: s.label,
                fit: format!("{:?}", s.fit),
            })
            .collect(),
        edges: graph
            .edges()
            .zip(&seg.edges)
            .map(|((a, b, p), &(_, _, boundary))| EdgeOut {
                a,
                b,
                boundary,
                radius: p.radius,
                length: p.length,
            })
            .collect(),
        timings_ms: Timings {
            topology: ms(seg.timings.topology),
            sdf: ms(seg.timings.sdf),
            clustering: ms(seg.timings.clustering),
            graph_cut: ms(seg.timings.graph_cut),
            nodes: ms(seg.timings.nodes),
            total: segment_ms,
        },
        picture: out.display().to_string(),
    };
    // Write errors (a closed pipe) are errors, not panics.
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{}", serde_json::to_string_pretty(&report)?)?;
        return Ok(());
    }
    writeln!(
        out,
        "{}: {} triangles, volume {:.6} m³, {} clusters → {} segments, {} edges ({:.0} ms)",
        report.mesh,
        report.triangles,
        report.volume,
        report.clusters,
        report.nodes.len(),
        report.edges.len(),
        segment_ms
    )?;
    writeln!(
        out,
        "{:>4}  {:>28}  {:>12}  {:>8}  {:>6}  {:>9}  {:>3}",
        "node", "position (m)", "capacity m³", "radius m", "faces", "area m²", "k"
    )?;
    for n in &report.nodes {
        writeln!(
            out,
            "{:>4}  ({:>+7.3}, {:>+7.3}, {:>+7.3})  {:>12.6}  {:>8.4}  {:>6}  {:>9.4}  {:>3}",
            n.index,
            n.position[0],
            n.position[1],
            n.position[2],
            n.capacity,
            n.radius,
            n.faces,
            n.area,
            n.cluster
        )?;
    }
    writeln!(
        out,
        "{:>4}  {:>4}  {:>10}  {:>10}  {:>10}",
        "a", "b", "boundary m", "pipe r m", "pipe L m"
    )?;
    for e in &report.edges {
        writeln!(
            out,
            "{:>4}  {:>4}  {:>10.4}  {:>10.4}  {:>10.4}",
            e.a, e.b, e.boundary, e.radius, e.length
        )?;
    }
    writeln!(out, "picture: {}", report.picture)?;
    if let Some(path) = &args.graph {
        writeln!(out, "graph file: {}", path.display())?;
    }
    Ok(())
}

/// A picture being drawn.
struct Picture {
    image: RgbImage,
}

impl Picture {
    fn write(&self, path: &Path) -> anyhow::Result<()> {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
        }
        self.image
            .save_with_format(path, image::ImageFormat::Png)
            .with_context(|| format!("writing {}", path.display()))
    }
}

/// An orthographic view: screen right and up axes, towards the viewer.
struct View {
    name: &'static str,
    right: Vector3<f64>,
    up: Vector3<f64>,
    toward: Vector3<f64>,
}

fn views() -> [View; 3] {
    [
        View {
            name: "front (+z)",
            right: Vector3::x(),
            up: Vector3::y(),
            toward: Vector3::z(),
        },
        View {
            name: "side (+x)",
            right: -Vector3::z(),
            up: Vector3::y(),
            toward: Vector3::x(),
        },
        View {
            name: "top (+y)",
            right: Vector3::x(),
            up: -Vector3::z(),
            toward: Vector3::y(),
        },
    ]
}

fn colour_of(i: usize) -> Rgb<u8> {
    let c = palette(i);
    Rgb([c.0, c.1, c.2])
}

fn shade(c: Rgb<u8>, f: f64) -> Rgb<u8> {
    Rgb(c.0.map(|v| (v as f64 * f).round().clamp(0.0, 255.0) as u8))
}

fn draw(mesh: &Mesh, seg: &Segmentation, graph: &LiquidGraph, size: u32) -> anyhow::Result<Picture> {
    let (lo, hi) = mesh.bounds();
    let centre = Point3::from((lo.coords + hi.coords) * 0.5);
    let extent = (hi - lo).max().max(1e-9);
    let margin = 24.0;
    let scale = (size as f64 - 2.0 * margin) / extent;
    let label_h = 22;
    let (w, h) = (3 * size, size + label_h);
    let mut image = RgbImage::from_pixel(w, h, Rgb([255, 255, 255]));
    let light = Vector3::new(0.3, 0.6, 0.75).normalize();
    let max_capacity = graph.nodes().map(|n| n.capacity).fold(0.0, f64::max);
    for (k, view) in views().iter().enumerate() {
        let x0 = (k as u32 * size) as f64;
        let project = |p: &Point3<f64>| -> (f64, f64, f64) {
            let d = p - centre;
            (
                x0 + size as f64 / 2.0 + d.dot(&view.right) * scale,
                label_h as f64 + size as f64 / 2.0 - d.dot(&view.up) * scale,
                d.dot(&view.toward),
            )
        };
        let mut depth = vec![f64::NEG_INFINITY; (size * size) as usize];
        for (t, tri) in mesh.triangles.iter().enumerate() {
            let [a, b, c] = tri.map(|v| mesh.positions[v as usize]);
            let n = (b - a).cross(&(c - a));
            let Some(n) = n.try_normalize(0.0) else { continue };
            let lit = 0.35 + 0.65 * n.dot(&light).abs();
            let colour = shade(colour_of(seg.face_segment[t] as usize), lit);
            let [pa, pb, pc] = [a, b, c].map(|p| project(&p));
            fill_triangle(
                &mut image,
                &mut depth,
                x0 as u32,
                size,
                label_h,
                [pa, pb, pc],
                colour,
            );
        }
        // The graph over the mesh.
        let positions: Vec<(f64, f64, f64)> = graph.nodes().map(|n| project(&n.position)).collect();
        for (a, b, _) in graph.edges() {
            line(&mut image, positions[a], positions[b], 3.0, Rgb([20, 20, 20]));
        }
        for (i, (n, p)) in graph.nodes().zip(&positions).enumerate() {
            let r = if max_capacity > 0.0 {
                4.0 + 14.0 * (n.capacity / max_capacity).cbrt()
            } else {
                4.0
            };
            disc(&mut image, p.0, p.1, r + 2.0, Rgb([20, 20, 20]));
            disc(&mut image, p.0, p.1, r, Rgb([255, 255, 255]));
            disc(&mut image, p.0, p.1, (r - 4.0).max(1.5), colour_of(i));
            text(
                &mut image,
                p.0 + r + 3.0,
                p.1 - r,
                &i.to_string(),
                3,
                Rgb([0, 0, 0]),
            );
        }
        text(&mut image, x0 + 8.0, 4.0, view.name, 3, Rgb([60, 60, 60]));
    }
    Ok(Picture { image })
}

/// Fills a projected triangle with a depth test (larger depth is nearer).
fn fill_triangle(
    image: &mut RgbImage,
    depth: &mut [f64],
    x0: u32,
    size: u32,
    top: u32,
    p: [(f64, f64, f64); 3],
    colour: Rgb<u8>,
) {
    let min_x = p
        .iter()
        .map(|q| q.0)
        .fold(f64::INFINITY, f64::min)
        .floor()
        .max(x0 as f64) as i64;
    let max_x = p
        .iter()
        .map(|q| q.0)
        .fold(f64::NEG_INFINITY, f64::max)
        .ceil()
        .min((x0 + size - 1) as f64) as i64;
    let min_y = p
        .iter()
        .map(|q| q.1)
        .fold(f64::INFINITY, f64::min)
        .floor()
        .max(top as f64) as i64;
    let max_y = p
        .iter()
        .map(|q| q.1)
        .fold(f64::NEG_INFINITY, f64::max)
        .ceil()
        .min((top + size - 1) as f64) as i64;
    let area = (p[1].0 - p[0].0) * (p[2].1 - p[0].1) - (p[2].0 - p[0].0) * (p[1].1 - p[0].1);
    if area.abs() < 1e-12 {
        return;
    }
    for y in min_y..=max_y {
        for x in min_x..=max_x {
            let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
            let w0 = ((p[1].0 - px) * (p[2].1 - py) - (p[2].0 - px) * (p[1].1 - py)) / area;
            let w1 = ((p[2].0 - px) * (p[0].1 - py) - (p[0].0 - px) * (p[2].1 - py)) / area;
            let w2 = 1.0 - w0 - w1;
            if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                continue;
            }
            let z = w0 * p[0].2 + w1 * p[1].2 + w2 * p[2].2;
            let k = ((y as u32 - top) * size + (x as u32 - x0)) as usize;
            if z > depth[k] {
                depth[k] = z;
                image.put_pixel(x as u32, y as u32, colour);
            }
        }
    }
}

fn put(image: &mut RgbImage, x: i64, y: i64, colour: Rgb<u8>) {
    if x >= 0 && y >= 0 && (x as u32) < image.width() && (y as u32) < image.height() {
        image.put_pixel(x as u32, y as u32, colour);
    }
}

fn disc(image: &mut RgbImage, cx: f64, cy: f64, r: f64, colour: Rgb<u8>) {
    let ri = r.ceil() as i64;
    for dy in -ri..=ri {
        for dx in -ri..=ri {
            if ((dx * dx + dy * dy) as f64) <= r * r {
                put(image, cx.round() as i64 + dx, cy.round() as i64 + dy, colour);
            }
        }
    }
}

fn line(image: &mut RgbImage, a: (f64, f64, f64), b: (f64, f64, f64), width: f64, colour: Rgb<u8>) {
    let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
    let steps = (len * 2.0).ceil().max(1.0) as usize;
    for i in 0..=steps {
        let t = i as f64 / steps as f64;
        disc(
            image,
            a.0 + t * (b.0 - a.0),
            a.1 + t * (b.1 - a.1),
            width / 2.0,
            colour,
        );
    }
}

/// 3×5 pixel glyphs for labels (digits, a few letters and signs).
fn glyph(c: char) -> [u8; 5] {
    match c.to_ascii_lowercase() {
        '0' => [7, 5, 5, 5, 7],
        '1' => [2, 6, 2, 2, 7],
        '2' => [7, 1, 7, 4, 7],
        '3' => [7, 1, 3, 1, 7],
        '4' => [5, 5, 7, 1, 1],
        '5' => [7, 4, 7, 1, 7],
        '6' => [7, 4, 7, 5, 7],
        '7' => [7, 1, 2, 2, 2],
        '8' => [7, 5, 7, 5, 7],
        '9' => [7, 5, 7, 1, 7],
        '+' => [0, 2, 7, 2, 0],
        '-' => [0, 0, 7, 0, 0],
        '(' => [1, 2, 2, 2, 1],
        ')' => [4, 2, 2, 2, 4],
        'a' => [2, 5, 7, 5, 5],
        'd' => [6, 5, 5, 5, 6],
        'e' => [7, 4, 6, 4, 7],
        'f' => [7, 4, 6, 4, 4],
        'i' => [7, 2, 2, 2, 7],
        'n' => [6, 5, 5, 5, 5],
        'o' => [2, 5, 5, 5, 2],
        'p' => [6, 5, 6, 4, 4],
        'r' => [6, 5, 6, 5, 5],
        's' => [3, 4, 2, 1, 6],
        't' => [7, 2, 2, 2, 2],
        'x' => [5, 5, 2, 5, 5],
        'y' => [5, 5, 2, 2, 2],
        'z' => [7, 1, 2, 4, 7],
        _ => [0; 5],
    }
}

fn text(image: &mut RgbImage, x: f64, y: f64, s: &str, px: i64, colour: Rgb<u8>) {
    let (x, y) = (x.round() as i64, y.round() as i64);
    for (k, c) in s.chars().enumerate() {
        let g = glyph(c);
        for (row, bits) in g.iter().enumerate() {
            for col in 0..3 {
                if bits & (4 >> col) != 0 {
                    for dy in 0..px {
                        for dx in 0..px {
                            put(
                                image,
                                x + (k as i64 * 4 + col) * px + dx,
                                y + row as i64 * px + dy,
                                colour,
                            );
                        }
                    }
                }
            }
        }
    }
}
