//! The window's side of the live view: winit's events for the [`App`]
//! (opening, input, redraws, closing), selection by the cursor, and the
//! frame read back from the window's surface.

use super::*;

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
    pub(super) fn touched(&mut self) {
        let now = Instant::now();
        self.input.get_or_insert(now);
        self.last_input = Some(now);
    }

    /// Selects the body under the cursor (or none).
    pub(super) fn select(&mut self) {
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
pub(super) fn modified(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}

/// Reads `texture` (8-bit, four channels, BGRA where `bgra`) back as RGBA.
pub(super) fn read_back(
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
