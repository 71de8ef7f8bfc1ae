//! `rollbeam static` and `rollbeam modes` (the work is `workflows::analyses`).

use std::path::PathBuf;

use std::path::Path;

use super::beam_only;
use crate::error::Error;
use crate::scene::Scene;
use crate::workflows::analyses::{default_mode_count, modes, statics};

#[derive(clap::Args)]
pub struct StaticArgs {
    scene: PathBuf,
    #[arg(long)]
    out: Option<PathBuf>,
}

/// `rollbeam static`.
pub fn static_command(args: StaticArgs) -> Result<(), Error> {
    let StaticArgs { scene: path, out } = args;
    let scene = Scene::load(&path)?;
    let setup = beam_only(&scene, &path, "static")?;
    let dir = out.unwrap_or_else(|| Path::new("out").join(&scene.name));
    let result = statics(&scene, setup, &dir)?;
    print!("{result}");
    Ok(())
}

#[derive(clap::Args)]
pub struct ModesArgs {
    scene: PathBuf,
    /// How many modes (default 6, or as many as a modal beam keeps or the mesh holds if fewer).
    #[arg(long)]
    count: Option<usize>,
    #[arg(long)]
    out: Option<PathBuf>,
}

/// `rollbeam modes`.
pub fn modes_command(args: ModesArgs) -> Result<(), Error> {
    let ModesArgs {
        scene: path,
        count,
        out,
    } = args;
    let scene = Scene::load(&path)?;
    let setup = beam_only(&scene, &path, "modes")?;
    let dir = out.unwrap_or_else(|| Path::new("out").join(&scene.name));
    let count = count.unwrap_or_else(|| default_mode_count(setup));
    let result = modes(&scene, setup, count, &dir)?;
    print!("{result}");
    Ok(())
}
