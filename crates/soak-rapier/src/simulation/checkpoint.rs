//! Checkpoint files: a saved run framed so that it is never half-loaded,
//! and files written whole or not at all.
//!
//! A checkpoint is an 8-byte magic (`SOAKCKPT`), the state format's
//! version (`u32`, little-endian), the payload's length in bytes (`u64`)
//! and its CRC-32 (`u32`), then the payload: JSON whose floats read back
//! bit for bit. [`read_checkpoint`] checks all four before it decodes a
//! byte of the payload, so a file of another program, of another version
//! of the state format, a truncated or a corrupted one is refused with a
//! [`CheckpointError`] that says which. [`write_checkpoint`] writes it with
//! [`write_atomically`]: a run killed while writing leaves the previous
//! checkpoint in place.

use std::io::Write;
use std::path::{Path, PathBuf};

use serde::Serialize;
use serde::de::DeserializeOwned;

/// The first eight bytes of every checkpoint.
pub const CHECKPOINT_MAGIC: [u8; 8] = *b"SOAKCKPT";

/// The state format's version: raised whenever what a checkpoint holds
/// changes, so that a file of another version is refused, not misread.
/// Version 2: a bake lays the texels of a texture block holding two
/// charts of the UV map as two tiles, so a body's per-texel state (its
/// liquid texture) follows another texel order than version 1's.
pub const CHECKPOINT_VERSION: u32 = 2;

/// Magic, version, length and checksum.
const HEADER: usize = 8 + 4 + 8 + 4;

/// A checkpoint could not be written, or was refused on reading.
#[derive(Debug, thiserror::Error)]
pub enum CheckpointError {
    /// The file could not be read, written or renamed into place.
    #[error("checkpoint `{path}`: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The file does not start with a checkpoint's magic bytes.
    #[error("`{path}` is not a soak checkpoint (it does not start with `SOAKCKPT`)")]
    NotACheckpoint {
        /// The file.
        path: PathBuf,
    },
    /// The file was written by a version of soak whose state format is
    /// another.
    #[error(
        "checkpoint `{path}` holds state format {found}, this soak reads format {expected}: resume it with the soak that wrote it, or start the run again"
    )]
    Version {
        /// The file.
        path: PathBuf,
        /// The format the file holds.
        found: u32,
        /// The format this build reads ([`CHECKPOINT_VERSION`]).
        expected: u32,
    },
    /// The file is shorter (or longer) than its header says.
    #[error("checkpoint `{path}` is truncated: {found} bytes of payload where its header says {expected}")]
    Truncated {
        /// The file.
        path: PathBuf,
        /// Payload bytes the header announces.
        expected: u64,
        /// Payload bytes the file has.
        found: u64,
    },
    /// The payload's checksum does not match the header's.
    #[error("checkpoint `{path}` is corrupted: its CRC-32 is {found:08x}, its header says {expected:08x}")]
    Checksum {
        /// The file.
        path: PathBuf,
        /// The header's checksum.
        expected: u32,
        /// The payload's.
        found: u32,
    },
    /// The payload passed its checksum but is not the state expected
    /// (a checkpoint of another command).
    #[error("checkpoint `{path}`: {source}")]
    Decode {
        /// The file.
        path: PathBuf,
        /// The JSON error.
        source: serde_json::Error,
    },
}

/// Writes `path` whole or not at all: `write` fills a temporary file beside
/// it (`.NAME.partial`), which is flushed to disk and renamed over `path`
/// only once `write` has succeeded. A run killed at any moment leaves
/// either the previous file or the new one under `path`, never part of
/// one; on an error the temporary file is removed.
///
/// # Errors
/// The I/O error of creating the directory, writing, syncing or renaming.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut std::io::BufWriter<std::fs::File>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let dir = path.parent().filter(|d| !d.as_os_str().is_empty());
    if let Some(dir) = dir {
        std::fs::create_dir_all(dir)?;
    }
    let name = path
        .file_name()
        .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::InvalidInput, "the path names no file"))?;
    let mut partial = std::ffi::OsString::from(".");
    partial.push(name);
    partial.push(".partial");
    let temporary = match dir {
        Some(dir) => dir.join(partial),
        None => PathBuf::from(partial),
    };
    let result = (|| {
        let mut w = std::io::BufWriter::new(std::fs::File::create(&temporary)?);
        write(&mut w)?;
        let file = w.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        std::fs::rename(&temporary, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&temporary);
    }
    result
}

/// Writes `payload` as a checkpoint at `path` (atomically, see the module
/// docs). Returns the file's size in bytes.
///
/// # Errors
/// [`CheckpointError::Io`] when the file cannot be written;
/// [`CheckpointError::Decode`] when the payload cannot be encoded.
pub fn write_checkpoint(path: &Path, payload: &impl Serialize) -> Result<u64, CheckpointError> {
    let body = serde_json::to_vec(payload).map_err(|source| CheckpointError::Decode {
        path: path.to_path_buf(),
        source,
    })?;
    write_atomically(path, |w| {
        w.write_all(&CHECKPOINT_MAGIC)?;
        w.write_all(&CHECKPOINT_VERSION.to_le_bytes())?;
        w.write_all(&(body.len() as u64).to_le_bytes())?;
        w.write_all(&crc32fast::hash(&body).to_le_bytes())?;
        w.write_all(&body)
    })
    .map_err(|source| CheckpointError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    Ok((HEADER + body.len()) as u64)
}

/// Reads a checkpoint [`write_checkpoint`] wrote: the magic, the version,
/// the length and the checksum are checked before the payload is decoded.
///
/// # Errors
/// One [`CheckpointError`] variant per way the file can be wrong.
pub fn read_checkpoint<T: DeserializeOwned>(path: &Path) -> Result<T, CheckpointError> {
    let bytes = std::fs::read(path).map_err(|source| CheckpointError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    decode_checkpoint(path, &bytes)
}

/// [`read_checkpoint`] of bytes already read (`path` names them in errors).
///
/// # Errors
/// As [`read_checkpoint`].
pub fn decode_checkpoint<T: DeserializeOwned>(path: &Path, bytes: &[u8]) -> Result<T, CheckpointError> {
    let path = || path.to_path_buf();
    if bytes.len() < 8 || bytes[..8] != CHECKPOINT_MAGIC {
        return Err(CheckpointError::NotACheckpoint { path: path() });
    }
    if bytes.len() < HEADER {
        return Err(CheckpointError::Truncated {
            path: path(),
            expected: 0,
            found: 0,
        });
    }
    let word = |at: usize| u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
    let version = word(8);
    if version != CHECKPOINT_VERSION {
        return Err(CheckpointError::Version {
            path: path(),
            found: version,
            expected: CHECKPOINT_VERSION,
        });
    }
    let mut length = [0u8; 8];
    length.copy_from_slice(&bytes[12..20]);
    let expected = u64::from_le_bytes(length);
    let body = &bytes[HEADER..];
    if body.len() as u64 != expected {
        return Err(CheckpointError::Truncated {
            path: path(),
            expected,
            found: body.len() as u64,
        });
    }
    let (expected, found) = (word(20), crc32fast::hash(body));
    if expected != found {
        return Err(CheckpointError::Checksum {
            path: path(),
            expected,
            found,
        });
    }
    serde_json::from_slice(body).map_err(|source| CheckpointError::Decode { path: path(), source })
}
