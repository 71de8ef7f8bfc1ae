//! `rollbeam tradeoff`: the work–precision of a scene (the work is `workflows::tradeoff`).

use std::path::{Path, PathBuf};

use crate::error::Error;
use crate::say;
use crate::scene::Scene;
use crate::workflows::tradeoff::{run_tradeoff, TradeoffOptions};

#[derive(clap::Args)]
pub struct TradeoffArgs {
    scene: PathBuf,
    /// Output folder (default out/<scene name>-tradeoff).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Methods to try, comma-separated (default: every one that fits the scene; on a beam all but
    /// dopri5, which the stiffest mode holds to tiny steps).
    #[arg(long, value_delimiter = ',')]
    methods: Vec<String>,
    /// Relative tolerances to try, comma-separated (default 1e-2 to 1e-8, or 1e-6 on a beam).
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    rtols: Vec<f64>,
    /// Element counts to try on a beam, comma-separated (default: the scene's and half of it).
    #[arg(long, value_delimiter = ',')]
    elements: Vec<usize>,
    /// Element degrees to try on a beam, comma-separated (default: the scene's).
    #[arg(long, value_delimiter = ',')]
    orders: Vec<usize>,
    /// Beam models to try, comma-separated: exact, linear, modal:N (default: the scene's).
    #[arg(long, value_delimiter = ',')]
    models: Vec<String>,
    /// Steps a run may take before it gives up (default 20000 on a beam, 200000 on a curve).
    #[arg(long)]
    max_steps: Option<usize>,
    /// One more setting past the grid, METHOD:RTOL:ELEMENTS:DEGREE (e.g. esdirk4:1e-4:20:6),
    /// run once with ten times the step budget; repeat the flag for more. The windowed means'
    /// reference is made on a mesh finer than these too.
    #[arg(long = "point")]
    points: Vec<String>,
    /// Compute the reference again, even where a stored one serves, and store it in
    /// `references/` beside the scene file.
    #[arg(long)]
    reference: bool,
    /// Make the probes' windowed means a reference (ESDIRK4, or the method of the tightest
    /// `--point`, a decade below the tightest rtol tried, on twice the finest mesh tried at the
    /// highest degree, checked at a tenfold rtol and on a mesh half as fine) and store it with
    /// the scene's reference; the diagram is then also drawn in the means (tradeoff-means.svg).
    #[arg(long)]
    reference_means: bool,
}

/// `rollbeam tradeoff`.
pub fn tradeoff(args: TradeoffArgs) -> Result<(), Error> {
    let TradeoffArgs {
        scene: path,
        out,
        methods,
        rtols,
        elements,
        orders,
        models,
        max_steps,
        points,
        reference: recompute,
        reference_means: recompute_means,
    } = args;
    let scene = Scene::load(&path)?;
    let options = TradeoffOptions {
        methods,
        rtols,
        elements,
        orders,
        models,
        max_steps,
        points,
        recompute,
        recompute_means,
    };
    // The command that stores the reference: this one, asked to compute it again.
    let mut made_by = std::iter::once("rollbeam".to_string())
        .chain(std::env::args().skip(1))
        .collect::<Vec<_>>()
        .join(" ");
    made_by = made_by.replace(" --reference-means", "");
    if !recompute {
        made_by.push_str(" --reference");
    }
    let dir = out.unwrap_or_else(|| Path::new("out").join(format!("{}-tradeoff", scene.name)));
    let (_, lines) = run_tradeoff(&scene, Some(&path), &options, &dir, &made_by, true)?;
    for line in lines {
        say!("  {line}");
    }
    say!("  wrote {}", dir.display());
    Ok(())
}
