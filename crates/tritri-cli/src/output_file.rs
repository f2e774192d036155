//! Output files that are checked before the work and written atomically:
//! [`OutputFile::reserve`] creates a temporary file next to the
//! destination (so an unwritable path fails at once, before a long run),
//! and [`OutputFile::commit`] fills it and renames it into place, so a
//! reader never sees half a file and an interrupted run leaves none (the
//! temporary is registered with `tools::interrupt`).

use anyhow::Context;
use std::io::{BufWriter, Write};
use std::path::PathBuf;
use tritri_rtl::tools::interrupt;

/// A destination and its reserved temporary, or standard output (`-`).
pub enum OutputFile {
    Stdout,
    File {
        destination: PathBuf,
        temporary: PathBuf,
    },
}

impl OutputFile {
    /// Checks that `path` can be written by creating its temporary now.
    pub fn reserve(path: &str) -> anyhow::Result<OutputFile> {
        if path == "-" {
            return Ok(OutputFile::Stdout);
        }
        if path.is_empty() {
            anyhow::bail!("an empty path: give a file name, or - for standard output");
        }
        let destination = PathBuf::from(path);
        if destination.is_dir() {
            anyhow::bail!("cannot write {path}: it is a directory");
        }
        let name = destination
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let temporary = destination.with_file_name(format!(".{name}.tmp-{}", std::process::id()));
        interrupt::make_temporary(&temporary, |p| std::fs::File::create(p))
            .with_context(|| format!("cannot write {path}"))?;
        Ok(OutputFile::File {
            destination,
            temporary,
        })
    }

    /// [`OutputFile::reserve`], refused when `path` is one of `inputs` (the
    /// same file, by any name), so an output never replaces what the run
    /// reads.
    pub fn reserve_apart(path: &str, inputs: &[&str]) -> anyhow::Result<OutputFile> {
        refuse_input(path, inputs)?;
        OutputFile::reserve(path)
    }

    /// Writes the contents with `fill` and puts the file in place.
    pub fn commit(
        self,
        fill: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
    ) -> anyhow::Result<()> {
        match &self {
            OutputFile::Stdout => {
                let mut w = BufWriter::new(crate::stdout::Stdout);
                fill(&mut w)?;
                w.flush()?;
            }
            OutputFile::File {
                destination,
                temporary,
            } => {
                let mut w = BufWriter::new(
                    std::fs::File::create(temporary)
                        .with_context(|| format!("cannot write {}", destination.display()))?,
                );
                fill(&mut w).with_context(|| format!("writing {}", destination.display()))?;
                w.flush()
                    .with_context(|| format!("writing {}", destination.display()))?;
                std::fs::rename(temporary, destination)
                    .with_context(|| format!("cannot write {}", destination.display()))?;
                interrupt::unregister_temporary(temporary);
            }
        }
        Ok(())
    }

    /// Where a tool writes the file itself (the reserved temporary; `None`
    /// for standard output); [`OutputFile::commit_written`] puts it in place.
    pub fn temporary(&self) -> Option<&std::path::Path> {
        match self {
            OutputFile::Stdout => None,
            OutputFile::File { temporary, .. } => Some(temporary),
        }
    }

    /// Puts the temporary a tool has filled in place; returns its size.
    pub fn commit_written(self) -> anyhow::Result<u64> {
        let OutputFile::File {
            destination,
            temporary,
        } = &self
        else {
            return Ok(0);
        };
        let size = std::fs::metadata(temporary)
            .with_context(|| format!("{} was not written", destination.display()))?
            .len();
        std::fs::rename(temporary, destination)
            .with_context(|| format!("cannot write {}", destination.display()))?;
        interrupt::unregister_temporary(temporary);
        Ok(size)
    }
}

/// An output never committed (an error on the way) leaves no temporary;
/// a committed one has nothing left to remove.
impl Drop for OutputFile {
    fn drop(&mut self) {
        if let OutputFile::File { temporary, .. } = self {
            let _ = std::fs::remove_file(&*temporary);
            interrupt::unregister_temporary(temporary);
        }
    }
}

/// An error when `path` names the same file as one of `inputs` (compared
/// by device and inode, so `./a.off` and `a.off` are one file; names
/// that do not exist, `-` and the built-ins like `@torus` are no file).
pub fn refuse_input(path: &str, inputs: &[&str]) -> anyhow::Result<()> {
    use std::os::unix::fs::MetadataExt;
    let Ok(out) = std::fs::metadata(path) else {
        return Ok(());
    };
    for input in inputs {
        if let Ok(meta) = std::fs::metadata(input) {
            if meta.dev() == out.dev() && meta.ino() == out.ino() {
                anyhow::bail!("cannot write {path}: it is the input {input}, which this run reads");
            }
        }
    }
    Ok(())
}

/// Checks before the work that files can be written into the directory
/// `dir`, creating it if needed (a probe file is made and removed).
pub fn check_directory(dir: &std::path::Path) -> anyhow::Result<()> {
    if dir.as_os_str().is_empty() {
        anyhow::bail!("an empty path: give a directory");
    }
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let probe = dir.join(format!(".tritri-probe-{}", std::process::id()));
    std::fs::File::create(&probe)
        .with_context(|| format!("cannot write into {}", dir.display()))?;
    let _ = std::fs::remove_file(&probe);
    Ok(())
}
