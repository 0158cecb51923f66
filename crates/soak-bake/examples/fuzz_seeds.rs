//! Writes seed inputs for the fuzz targets (see `docs/fuzzing.md`): the
//! builtin meshes at low resolution as OBJ (with and without UVs), as glTF
//! with an embedded buffer and as GLB, and small PNG / OpenEXR images.
//!
//! ```text
//! cargo run -p soak-bake --example fuzz_seeds -- OUT_DIR
//! ```
//!
//! Files go to `OUT_DIR/obj`, `OUT_DIR/gltf` and `OUT_DIR/texture`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use image::{ImageBuffer, Luma, LumaA, Rgb, Rgb32FImage, Rgba};
use soak_bake::{Mesh, builtin};

/// Builtin names at resolutions that keep each file a few kilobytes.
const BUILTINS: &[&str] = &[
    "builtin:box",
    "builtin:box:2x1x1",
    "builtin:sphere:0.5:8:4",
    "builtin:cylinder:0.5:1:8",
    "builtin:capsule:0.25:0.5:6",
    "builtin:torus:0.5:0.15:8:4",
    "builtin:boat",
    "builtin:dumbbell:0.3:0.08:1.2:6",
];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = PathBuf::from(std::env::args_os().nth(1).ok_or("usage: fuzz_seeds OUT_DIR")?);
    for dir in ["obj", "gltf", "texture"] {
        std::fs::create_dir_all(out.join(dir))?;
    }
    for name in BUILTINS {
        let mesh = builtin::parse(name)?;
        let stem = name.trim_start_matches("builtin:").replace([':', '.'], "_");
        std::fs::write(out.join("obj").join(format!("{stem}.obj")), mesh.to_obj())?;
        let bare = Mesh {
            uvs: None,
            ..mesh.clone()
        };
        std::fs::write(out.join("obj").join(format!("{stem}_nouv.obj")), bare.to_obj())?;
        std::fs::write(out.join("gltf").join(format!("{stem}.glb")), glb(&mesh))?;
        std::fs::write(
            out.join("gltf").join(format!("{stem}.gltf")),
            gltf_embedded(&bare),
        )?;
    }
    images(&out.join("texture"))?;
    Ok(())
}

/// A glTF buffer: positions (f32 × 3), UVs (f32 × 2) if any, indices (u32,
/// or u16 when `short`), and the JSON describing it.
fn layout(mesh: &Mesh, short: bool, uri: Option<&str>) -> (String, Vec<u8>) {
    let n = mesh.positions.len();
    let mut bin = Vec::new();
    let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
    for p in &mesh.positions {
        for k in 0..3 {
            let v = p[k] as f32;
            lo[k] = lo[k].min(v);
            hi[k] = hi[k].max(v);
            bin.extend_from_slice(&v.to_le_bytes());
        }
    }
    let uv_offset = bin.len();
    if let Some(uvs) = &mesh.uvs {
        for uv in uvs {
            bin.extend_from_slice(&(uv.x as f32).to_le_bytes());
            bin.extend_from_slice(&(uv.y as f32).to_le_bytes());
        }
    }
    let index_offset = bin.len();
    for &i in mesh.triangles.iter().flatten() {
        if short {
            bin.extend_from_slice(&(i as u16).to_le_bytes());
        } else {
            bin.extend_from_slice(&i.to_le_bytes());
        }
    }
    let index_len = bin.len() - index_offset;
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let count = mesh.triangles.len() * 3;
    let component = if short { 5123 } else { 5125 };
    let uri = uri.map(|u| format!(",\"uri\":\"{u}\"")).unwrap_or_default();
    let mut j = String::new();
    let _ = write!(
        j,
        "{{\"asset\":{{\"version\":\"2.0\"}},\"scene\":0,\"scenes\":[{{\"nodes\":[0]}}],\
         \"nodes\":[{{\"mesh\":0}}],\"buffers\":[{{\"byteLength\":{}{uri}}}],\
         \"bufferViews\":[{{\"buffer\":0,\"byteOffset\":0,\"byteLength\":{},\"target\":34962}},\
         {{\"buffer\":0,\"byteOffset\":{index_offset},\"byteLength\":{index_len},\"target\":34963}}",
        bin.len(),
        12 * n,
    );
    if mesh.uvs.is_some() {
        let _ = write!(
            j,
            ",{{\"buffer\":0,\"byteOffset\":{uv_offset},\"byteLength\":{},\"target\":34962}}",
            8 * n
        );
    }
    let _ = write!(
        j,
        "],\"accessors\":[{{\"bufferView\":0,\"componentType\":5126,\"count\":{n},\"type\":\"VEC3\",\
         \"min\":{lo:?},\"max\":{hi:?}}},{{\"bufferView\":1,\"componentType\":{component},\
         \"count\":{count},\"type\":\"SCALAR\"}}"
    );
    let uv_attribute = if mesh.uvs.is_some() {
        let _ = write!(
            j,
            ",{{\"bufferView\":2,\"componentType\":5126,\"count\":{n},\"type\":\"VEC2\"}}"
        );
        ",\"TEXCOORD_0\":2"
    } else {
        ""
    };
    let _ = write!(
        j,
        "],\"meshes\":[{{\"primitives\":[{{\"attributes\":{{\"POSITION\":0{uv_attribute}}},\"indices\":1}}]}}]}}"
    );
    (j, bin)
}

/// A binary glTF (u32 indices) with its buffer in the BIN chunk.
fn glb(mesh: &Mesh) -> Vec<u8> {
    let (json, bin) = layout(mesh, false, None);
    let mut json = json.into_bytes();
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}

/// A JSON glTF (u16 indices) with its buffer as a base64 data URI.
fn gltf_embedded(mesh: &Mesh) -> String {
    let (_, bin) = layout(mesh, true, None);
    let uri = format!("data:application/octet-stream;base64,{}", base64(&bin));
    layout(mesh, true, Some(&uri)).0
}

fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let v = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                s.push(ALPHABET[(v >> (18 - 6 * k)) as usize & 63] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// Small images in the formats and channel layouts soak's textures come in.
fn images(dir: &Path) -> Result<(), image::ImageError> {
    let ramp = |x: u32, y: u32, w: u32| ((x + y * w) * 255 / (w * w - 1).max(1)) as u8;
    ImageBuffer::from_fn(1, 1, |_, _| Luma([200u8])).save(dir.join("gray_1x1.png"))?;
    ImageBuffer::from_fn(4, 4, |x, y| Luma([ramp(x, y, 4)])).save(dir.join("gray_4x4.png"))?;
    ImageBuffer::from_fn(8, 2, |x, _| Luma([(x * 8000) as u16])).save(dir.join("gray16_8x2.png"))?;
    ImageBuffer::from_fn(3, 3, |x, y| LumaA([ramp(x, y, 3), 128u8])).save(dir.join("gray_alpha_3x3.png"))?;
    ImageBuffer::from_fn(4, 4, |x, y| Rgb([ramp(x, y, 4), 0, 255 - ramp(x, y, 4)]))
        .save(dir.join("rgb_4x4.png"))?;
    ImageBuffer::from_fn(2, 2, |x, y| Rgba([255u8, 0, 0, ramp(x, y, 2)])).save(dir.join("rgba_2x2.png"))?;
    let mut exr = Rgb32FImage::new(2, 2);
    for (x, y, p) in exr.enumerate_pixels_mut() {
        *p = Rgb([x as f32 * 0.5, y as f32, 1.0]);
    }
    exr.save(dir.join("rgb_2x2.exr"))?;
    Ok(())
}
