//! [`GpuHydro`]: atlases resident on a device, in pages of storage buffers.

use std::sync::Mutex;

use nalgebra::Point3;
use soak_bake::Atlas;

use super::error::{GpuAtlasId, GpuHydroError};
use super::kernels::Kernels;
use super::layout::{ITEM_TEXELS, TEXEL_BYTES, TRIBARY_BYTES, texel_vec4s};
use soak_gpu::{GpuError, scoped};

/// Construction options of a [`GpuHydro`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct GpuOptions {
    /// Caps the bytes of one storage binding below the device's
    /// `max_storage_buffer_binding_size` (atlases larger than a page are
    /// split across pages). `None` uses the device's limit.
    pub max_storage_binding: Option<u64>,
}

impl GpuOptions {
    /// Options with the storage binding limit lowered to `bytes`.
    pub fn with_max_storage_binding(mut self, bytes: u64) -> Self {
        self.max_storage_binding = Some(bytes);
        self
    }
}

/// A storage buffer that holds texels of one or more atlases.
pub(crate) struct Page {
    /// Two vec4s per texel: `(x − origin, |A|)` and `(A, 0)`.
    pub texels: wgpu::Buffer,
    /// One vec4 per texel: `(bits of triangle id, λ1, λ2, 0)`.
    pub tribary: wgpu::Buffer,
    /// Texels the buffers hold.
    pub capacity: u32,
    /// Texels in use.
    pub used: u32,
}

/// A run of an atlas's texels in one page.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Segment {
    pub page: usize,
    /// First texel in the page.
    pub start: u32,
    pub len: u32,
    /// Atlas-local index of the first texel.
    pub offset: u32,
}

/// What a deformable atlas keeps on the device.
pub(crate) struct Deformable {
    /// Per triangle: vertex indices and texel count.
    pub triangles: wgpu::Buffer,
    /// Vertex positions relative to the origin.
    pub vertices: wgpu::Buffer,
    pub vertex_count: usize,
}

pub(crate) struct Entry {
    pub origin: Point3<f64>,
    /// Radius of a sphere about the origin that holds every texel, m: the
    /// atlas's, or after a deformation one that holds every vertex.
    pub radius: f64,
    /// The atlas' mean thickness ([`Atlas::mean_thickness`]) as uploaded,
    /// m: with the radius, the depth past which a texel counts as deep
    /// (`deep_scale`; a deformation keeps the uploaded one).
    pub thickness: f64,
    pub len: usize,
    pub segments: Vec<Segment>,
    pub deformable: Option<Deformable>,
    /// The moments of the atlas' tiles as uploaded, for the section a sea
    /// read as one plane takes ([`crate::SeaSampling::Plane`]); `None`
    /// once the device has deformed it (the plane then takes the disc of
    /// the bounding radius).
    pub tiles: Option<(Vec<nalgebra::Vector3<f64>>, Vec<soak_bake::MomentSums>)>,
    /// For an open mesh's atlas: 1 on the walls, 0 on the caps (which
    /// carry no mass).
    pub walls: Option<Vec<f32>>,
}

/// A buffer that grows (never shrinks) to what a call needs.
pub(crate) struct Grow {
    buffer: Option<wgpu::Buffer>,
    capacity: u64,
    usage: wgpu::BufferUsages,
    label: &'static str,
}

impl Grow {
    pub(crate) fn new(label: &'static str, usage: wgpu::BufferUsages) -> Self {
        Self {
            buffer: None,
            capacity: 0,
            usage,
            label,
        }
    }

    pub(crate) fn storage(label: &'static str) -> Self {
        Self::new(
            label,
            wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
        )
    }

    /// The buffer, reallocated if it holds fewer than `bytes` bytes (at most
    /// `cap` bytes when doubling). Call inside an error scope.
    pub(crate) fn ensure(&mut self, device: &wgpu::Device, bytes: u64, cap: u64) -> &wgpu::Buffer {
        let bytes = bytes.max(256).next_multiple_of(256);
        if self.buffer.is_none() || bytes > self.capacity {
            let size = bytes.max((self.capacity * 2).min(cap)).next_multiple_of(256);
            self.buffer = Some(device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(self.label),
                size,
                usage: self.usage,
                mapped_at_creation: false,
            }));
            self.capacity = size;
        }
        self.buffer.as_ref().expect("allocated above")
    }

    pub(crate) fn get(&self) -> &wgpu::Buffer {
        self.buffer.as_ref().expect("ensured before use")
    }
}

/// Per-call buffers, reused between calls.
pub(crate) struct Scratch {
    pub bodies: Grow,
    pub waves: Grow,
    pub heights: Grow,
    pub items: Grow,
    pub dispatch: Grow,
    pub partials: Grow,
    pub ranges: Grow,
    pub results: Grow,
    pub densities: Grow,
    pub staging: Grow,
    /// A spectral sea's turned amplitudes, its uniforms and its two
    /// buffers of transformed layers ([`super::sea`]): allocated on the
    /// first batch that reads a sea on the device.
    pub sea_modes: Grow,
    pub sea_uniforms: Grow,
    pub sea_spec: Grow,
    pub sea_scratch: Grow,
}

impl Scratch {
    fn new() -> Self {
        Self {
            bodies: Grow::storage("soak bodies"),
            waves: Grow::storage("soak waves"),
            heights: Grow::storage("soak heights"),
            items: Grow::storage("soak items"),
            dispatch: Grow::new(
                "soak dispatch",
                wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            ),
            partials: Grow::storage("soak partials"),
            ranges: Grow::storage("soak ranges"),
            results: Grow::storage("soak results"),
            densities: Grow::storage("soak densities"),
            sea_modes: Grow::storage("soak sea modes"),
            sea_uniforms: Grow::new(
                "soak sea uniforms",
                wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            ),
            sea_spec: Grow::storage("soak sea layers"),
            sea_scratch: Grow::storage("soak sea scratch"),
            staging: Grow::new(
                "soak readback",
                wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            ),
        }
    }
}

/// Hydrostatics, drag and mass properties on a wgpu device.
///
/// Upload an atlas once ([`GpuHydro::upload`]); then each step only poses,
/// velocities and water parameters go up, and a few floats per body come
/// back. The per-texel sums are those of [`crate::evaluate`], in f32 with
/// positions relative to the atlas origin, reduced in two passes on the
/// device; the CPU turns them into forces with the same code as
/// [`crate::evaluate`] (the implicit drag solve included).
///
/// Atlases live in pages of storage buffers no larger than the device's
/// `max_storage_buffer_binding_size` (or [`GpuOptions::max_storage_binding`]);
/// an atlas larger than a page is split across pages.
///
/// `evaluate` takes `&self` and may be called from several threads; calls
/// on one `GpuHydro` take turns. On wgpu's GL backend a device serialises
/// all work behind one context lock held through each submission, and wgpu
/// panics when a thread waits more than 6 s for it: do not share a GL device
/// between threads that submit long batches on a software adapter.
///
/// # Example
/// ```no_run
/// use nalgebra::Isometry3;
/// use soak_bake::{Atlas, BakeOptions, builtin};
/// use soak_hydro::gpu::{GpuHydro, headless_device};
/// use soak_hydro::prelude::*;
///
/// let (device, queue, _info) = headless_device()?;
/// let mut gpu = GpuHydro::new(&device, &queue)?;
/// let atlas = Atlas::bake(&builtin::cuboid(1.0, 1.0, 1.0), BakeOptions::square(128))?;
/// let id = gpu.upload(&atlas)?;
/// let mass = MassModel::Solid { density: 500.0 }.mass_properties(&atlas)?;
/// let state = BodyState::at_rest(Isometry3::translation(0.0, -0.2, 0.0));
/// let f = gpu.evaluate(id, &Water::calm(0.0), &state, &mass, 0.0, &HydroOptions::default())?;
/// assert!((f.submerged_volume - 0.7).abs() < 1e-5);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct GpuHydro {
    pub(crate) device: wgpu::Device,
    pub(crate) queue: wgpu::Queue,
    pub(crate) kernels: Kernels,
    /// Bytes of one storage binding.
    pub(crate) limit: u64,
    /// Texels of one page.
    pub(crate) page_texels: u32,
    pub(crate) pages: Vec<Page>,
    pub(crate) atlases: Vec<Entry>,
    /// Per atlas slot, the bits of the squared bounding radius (f32).
    pub(crate) radii: wgpu::Buffer,
    pub(crate) radii_capacity: u32,
    pub(crate) scratch: Mutex<Scratch>,
}

impl std::fmt::Debug for GpuHydro {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuHydro")
            .field("limit", &self.limit)
            .field("pages", &self.pages.len())
            .field("atlases", &self.atlases.len())
            .finish_non_exhaustive()
    }
}

// Engines share one GpuHydro between threads.
const _: () = {
    const fn send_sync<T: Send + Sync>() {}
    send_sync::<GpuHydro>();
};

/// The smallest storage binding limit that holds one work item of texels.
const MIN_LIMIT: u64 = ITEM_TEXELS as u64 * TEXEL_BYTES;

impl GpuHydro {
    /// Compiles the kernels on `device`, with the device's limits.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Result<Self, GpuHydroError> {
        Self::with_options(device, queue, GpuOptions::default())
    }

    /// Compiles the kernels on `device` with `options`.
    pub fn with_options(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        options: GpuOptions,
    ) -> Result<Self, GpuHydroError> {
        let limits = device.limits();
        let mut limit = limits.max_storage_buffer_binding_size.min(limits.max_buffer_size);
        if let Some(cap) = options.max_storage_binding {
            limit = limit.min(cap);
        }
        let limit = limit / 256 * 256;
        if limit < MIN_LIMIT {
            return Err(GpuError::LimitTooSmall {
                limit,
                minimum: MIN_LIMIT,
            }
            .into());
        }
        let kernels = Kernels::new(device)?;
        let radii = scoped::<_, GpuHydroError>(device, "allocating the radius buffer", 256, || {
            Ok(radii_buffer(device, 64))
        })?;
        Ok(Self {
            device: device.clone(),
            queue: queue.clone(),
            kernels,
            limit,
            page_texels: (limit / TEXEL_BYTES).min(u32::MAX as u64 / 2) as u32,
            pages: Vec::new(),
            atlases: Vec::new(),
            radii,
            radii_capacity: 64,
            scratch: Mutex::new(Scratch::new()),
        })
    }

    /// Bytes of one storage binding in force (device limit or the option).
    pub fn storage_binding_limit(&self) -> u64 {
        self.limit
    }

    /// Number of pages (storage buffers of texels) in use.
    pub fn page_count(&self) -> usize {
        self.pages.len()
    }

    /// Number of pages the atlas `id` spans (more than one when it was split).
    pub fn atlas_pages(&self, id: GpuAtlasId) -> Result<usize, GpuHydroError> {
        Ok(self.entry(id)?.segments.len())
    }

    pub(crate) fn entry(&self, id: GpuAtlasId) -> Result<&Entry, GpuHydroError> {
        self.atlases
            .get(id.0 as usize)
            .ok_or(GpuHydroError::UnknownAtlas(id))
    }

    /// Uploads an atlas's texels (positions relative to its origin and area
    /// vectors), once; evaluate it by the returned id.
    pub fn upload(&mut self, atlas: &Atlas) -> Result<GpuAtlasId, GpuHydroError> {
        self.upload_inner(atlas, None)
    }

    /// Uploads an atlas with the triangles (vertex indices) of the mesh it
    /// was baked from, so [`GpuHydro::deform`] can move its texels on the
    /// device. `triangles` are `Mesh::triangles` of that mesh. A coarsened
    /// atlas is refused ([`GpuHydroError::Coarsened`]): its samples are not
    /// on single triangles.
    pub fn upload_deformable(
        &mut self,
        atlas: &Atlas,
        triangles: &[[u32; 3]],
    ) -> Result<GpuAtlasId, GpuHydroError> {
        let bad = |triangle: usize, detail: &'static str| GpuHydroError::Triangles {
            triangle,
            detail,
            triangles: atlas.triangle_count(),
            vertices: atlas.vertex_count(),
        };
        if let Some(factor) = atlas.coarsening() {
            return Err(GpuHydroError::Coarsened { factor });
        }
        if triangles.len() != atlas.triangle_count() {
            return Err(bad(triangles.len(), "count given"));
        }
        if let Some(t) = triangles
            .iter()
            .position(|t| t.iter().any(|&v| v as usize >= atlas.vertex_count()))
        {
            return Err(bad(t, "vertex index out of range"));
        }
        for (what, needed) in [
            ("the triangles of a deformable atlas", triangles.len() as u64 * 16),
            (
                "the vertices of a deformable atlas",
                atlas.vertex_count() as u64 * 16,
            ),
        ] {
            if needed > self.limit {
                return Err(GpuError::TooLarge {
                    what,
                    needed,
                    limit: self.limit,
                }
                .into());
            }
        }
        self.upload_inner(atlas, Some(triangles))
    }

    fn upload_inner(
        &mut self,
        atlas: &Atlas,
        triangles: Option<&[[u32; 3]]>,
    ) -> Result<GpuAtlasId, GpuHydroError> {
        let n = atlas.len();
        if n == 0 {
            return Err(GpuHydroError::EmptyAtlas);
        }
        if n >= (u32::MAX / 2) as usize {
            return Err(GpuError::TooLarge {
                what: "an atlas",
                needed: n as u64 * TEXEL_BYTES,
                limit: (u32::MAX / 2) as u64 * TEXEL_BYTES,
            }
            .into());
        }
        let texels = texel_vec4s(atlas);
        let tribary: Vec<[f32; 4]> = atlas
            .triangle_ids()
            .iter()
            .zip(atlas.barycentrics())
            .map(|(&t, b)| [f32::from_bits(t), b[0], b[1], 0.0])
            .collect();
        let device = self.device.clone();
        let bytes = n as u64 * (TEXEL_BYTES + TRIBARY_BYTES);
        scoped::<_, GpuHydroError>(&device, "uploading an atlas", bytes, || {
            let segments = self.place(&texels, &tribary);
            let slot = self.atlases.len() as u32;
            self.ensure_radii(slot + 1);
            let r = atlas.bounding_radius() as f32;
            self.queue.write_buffer(
                &self.radii,
                slot as u64 * 4,
                bytemuck::bytes_of(&(r * r).to_bits()),
            );
            let deformable = triangles.map(|tris| self.deformable(atlas, tris));
            self.atlases.push(Entry {
                origin: atlas.origin(),
                radius: atlas.bounding_radius(),
                thickness: atlas.mean_thickness(),
                len: n,
                segments,
                deformable,
                tiles: Some((atlas.tile_centres().to_vec(), atlas.tile_moment_sums().to_vec())),
                walls: atlas.has_openings().then(|| {
                    (0..n)
                        .map(|i| if atlas.is_opening(i) { 0.0 } else { 1.0 })
                        .collect()
                }),
            });
            Ok(GpuAtlasId(slot))
        })
    }

    /// Writes texels into pages (filling the last page, growing it up to a
    /// page, then opening new ones) and returns where they went.
    fn place(&mut self, texels: &[[f32; 4]], tribary: &[[f32; 4]]) -> Vec<Segment> {
        let n = tribary.len() as u32;
        let mut segments = Vec::new();
        let mut done = 0u32;
        while done < n {
            if self.pages.last().is_none_or(|p| p.used >= self.page_texels) {
                let capacity = (n - done).clamp(65536.min(self.page_texels), self.page_texels);
                let page = self.new_page(capacity);
                self.pages.push(page);
            }
            let index = self.pages.len() - 1;
            let used = self.pages[index].used;
            let k = (n - done).min(self.page_texels - used);
            if used + k > self.pages[index].capacity {
                let capacity = (used + k)
                    .max(self.pages[index].capacity.saturating_mul(2))
                    .min(self.page_texels);
                self.grow_page(index, capacity);
            }
            let page = &mut self.pages[index];
            let (a, b) = (done as usize, (done + k) as usize);
            self.queue.write_buffer(
                &page.texels,
                used as u64 * TEXEL_BYTES,
                bytemuck::cast_slice(&texels[2 * a..2 * b]),
            );
            self.queue.write_buffer(
                &page.tribary,
                used as u64 * TRIBARY_BYTES,
                bytemuck::cast_slice(&tribary[a..b]),
            );
            segments.push(Segment {
                page: index,
                start: used,
                len: k,
                offset: done,
            });
            page.used += k;
            done += k;
        }
        segments
    }

    fn new_page(&self, capacity: u32) -> Page {
        let buffer = |label, bytes| {
            self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage: wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::COPY_DST
                    | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        Page {
            texels: buffer("soak texels", capacity as u64 * TEXEL_BYTES),
            tribary: buffer("soak triangle ids", capacity as u64 * TRIBARY_BYTES),
            capacity,
            used: 0,
        }
    }

    fn grow_page(&mut self, index: usize, capacity: u32) {
        let mut page = self.new_page(capacity);
        let old = &self.pages[index];
        page.used = old.used;
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None });
        encoder.copy_buffer_to_buffer(&old.texels, 0, &page.texels, 0, old.used as u64 * TEXEL_BYTES);
        encoder.copy_buffer_to_buffer(&old.tribary, 0, &page.tribary, 0, old.used as u64 * TRIBARY_BYTES);
        self.queue.submit([encoder.finish()]);
        self.pages[index] = page;
    }

    fn ensure_radii(&mut self, slots: u32) {
        if slots <= self.radii_capacity {
            return;
        }
        let capacity = slots.max(self.radii_capacity * 2);
        let radii = radii_buffer(&self.device, capacity);
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None });
        encoder.copy_buffer_to_buffer(&self.radii, 0, &radii, 0, self.radii_capacity as u64 * 4);
        self.queue.submit([encoder.finish()]);
        self.radii = radii;
        self.radii_capacity = capacity;
    }

    fn deformable(&self, atlas: &Atlas, triangles: &[[u32; 3]]) -> Deformable {
        let tris: Vec<[u32; 4]> = triangles
            .iter()
            .zip(atlas.texels_per_triangle())
            .map(|(t, &n)| [t[0], t[1], t[2], n])
            .collect();
        let buffer = |label, bytes: u64| {
            self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes.max(16),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let tri_buffer = buffer("soak triangles", tris.len() as u64 * 16);
        self.queue
            .write_buffer(&tri_buffer, 0, bytemuck::cast_slice(&tris));
        Deformable {
            triangles: tri_buffer,
            vertices: buffer("soak vertices", atlas.vertex_count() as u64 * 16),
            vertex_count: atlas.vertex_count(),
        }
    }
}

fn radii_buffer(device: &wgpu::Device, slots: u32) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("soak radii"),
        size: slots as u64 * 4,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    })
}
