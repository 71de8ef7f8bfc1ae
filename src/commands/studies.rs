//! `rollbeam studies`: every study of the thesis and the report's figures (the work is
//! `workflows::studies`).

use std::path::{Path, PathBuf};

use crate::error::Error;
use crate::say;
use crate::workflows::studies::{run_all, store_references};

#[derive(clap::Args)]
pub struct StudiesArgs {
    /// Folder for the runs (default out).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Leave out the work–precision diagrams.
    #[arg(long)]
    no_work_precision: bool,
    /// First compute every study's work–precision reference again and store it under
    /// studies/references/ (about an hour on two cores); otherwise the stored ones serve.
    #[arg(long)]
    references: bool,
}

/// `rollbeam studies`.
pub fn studies(args: StudiesArgs) -> Result<(), Error> {
    let StudiesArgs {
        out,
        no_work_precision,
        references,
    } = args;
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let here = if Path::new("studies").is_dir() {
        Path::new(".")
    } else {
        root
    };
    let out = out.unwrap_or_else(|| here.join("out"));
    let started = std::time::Instant::now();
    if references {
        store_references(&here.join("studies"))?;
    }
    run_all(
        &here.join("studies"),
        &out,
        &here.join("report").join("figures"),
        !no_work_precision,
    )?;
    say!("studies: done in {:.1} s", started.elapsed().as_secs_f64());
    Ok(())
}
