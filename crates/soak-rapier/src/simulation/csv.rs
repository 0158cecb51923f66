//! The time series of a run as CSV, written as the run makes its rows.

use std::io::{Seek, Write};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use super::{Sample, Simulation};

/// The CSV's header line (units in the column names), its line end included.
pub const CSV_HEADER: &str = "t_s,body,x_m,y_m,z_m,qx,qy,qz,qw,vx_m_s,vy_m_s,vz_m_s,wx_rad_s,wy_rad_s,wz_rad_s,\
buoyancy_x_n,buoyancy_y_n,buoyancy_z_n,drag_x_n,drag_y_n,drag_z_n,submerged_volume_m3,mass_kg,liquid_inside_m3,\
surface_liquid_m3\n";

impl Sample {
    /// This sample's CSV row (the columns of [`CSV_HEADER`]) for the body
    /// named `name`, its line end included.
    pub fn csv_row(&self, name: &str) -> String {
        let f = |v: &[f64]| v.iter().map(|x| format!("{x:.6}")).collect::<Vec<_>>().join(",");
        format!(
            "{:.5},{},{},{},{},{},{},{},{:.6},{:.4},{:.6},{:.9}\n",
            self.t,
            name,
            f(&self.position),
            f(&self.rotation),
            f(&self.linear_velocity),
            f(&self.angular_velocity),
            f(&self.buoyancy),
            f(&self.drag),
            self.submerged_volume,
            self.mass,
            self.liquid_inside,
            self.surface_liquid
        )
    }
}

/// A run's samples streamed to a CSV file as they are made: rows are
/// handed to the file at least once a second (so a run killed at any
/// moment keeps what it had written up to a second before), and
/// [`SampleCsv::sync`] puts them on disk and says how many bytes a
/// checkpoint may count on.
#[derive(Debug)]
pub struct SampleCsv {
    path: PathBuf,
    writer: std::io::BufWriter<std::fs::File>,
    /// Bytes written so far (buffered included).
    bytes: u64,
    last_flush: Instant,
}

impl SampleCsv {
    /// A new file (its directory made) with its header.
    pub fn create(path: &Path) -> std::io::Result<Self> {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)?;
        }
        let file = std::fs::File::create(path)?;
        let mut csv = Self {
            path: path.to_path_buf(),
            writer: std::io::BufWriter::new(file),
            bytes: 0,
            last_flush: Instant::now(),
        };
        csv.write(CSV_HEADER)?;
        Ok(csv)
    }

    /// The file a checkpoint left at `bytes`: cut back to them (rows
    /// written after the checkpoint are written again) and continued. A
    /// file shorter than `bytes` was changed since, and is refused
    /// (`ErrorKind::InvalidData`).
    pub fn resume(path: &Path, bytes: u64) -> std::io::Result<Self> {
        let mut file = std::fs::OpenOptions::new().read(true).write(true).open(path)?;
        let len = file.metadata()?.len();
        if len < bytes {
            return Err(std::io::Error::new(
                std::io::ErrorKind::InvalidData,
                format!(
                    "the CSV {} has {len} bytes, fewer than the {bytes} it had at the checkpoint: it was changed since; start the run again",
                    path.display()
                ),
            ));
        }
        file.set_len(bytes)?;
        file.seek(std::io::SeekFrom::End(0))?;
        Ok(Self {
            path: path.to_path_buf(),
            writer: std::io::BufWriter::new(file),
            bytes,
            last_flush: Instant::now(),
        })
    }

    /// The file written.
    pub fn path(&self) -> &Path {
        &self.path
    }

    fn write(&mut self, text: &str) -> std::io::Result<()> {
        self.writer.write_all(text.as_bytes())?;
        self.bytes += text.len() as u64;
        Ok(())
    }

    /// Appends the rows of `samples` (bodies named as in `sim`), and hands
    /// them to the file if the last flush is a second old.
    pub fn rows(&mut self, sim: &Simulation, samples: &[Sample]) -> std::io::Result<()> {
        for s in samples {
            let name = sim.bodies.get(s.body).map_or("?", |b| b.name.as_str());
            self.write(&s.csv_row(name))?;
        }
        if self.last_flush.elapsed() >= Duration::from_secs(1) {
            self.flush()?;
        }
        Ok(())
    }

    /// Hands what is buffered to the file.
    pub fn flush(&mut self) -> std::io::Result<()> {
        self.writer.flush()?;
        self.last_flush = Instant::now();
        Ok(())
    }

    /// Flushed and on disk: the bytes a checkpoint may count on.
    pub fn sync(&mut self) -> std::io::Result<u64> {
        self.flush()?;
        self.writer.get_ref().sync_data()?;
        Ok(self.bytes)
    }
}
