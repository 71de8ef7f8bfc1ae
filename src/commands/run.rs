//! `rollbeam run`: one scene, its outputs written and a few lines printed.

use std::path::{Path, PathBuf};

use super::SolverFlags;
use crate::error::Error;
use crate::output;
use crate::run::{self, Overrides, Run};
use crate::say;
use crate::scene::Scene;

#[derive(clap::Args)]
pub struct RunArgs {
    scene: PathBuf,
    /// Output folder (default out/<scene name>).
    #[arg(long)]
    out: Option<PathBuf>,
    #[command(flatten)]
    solver: SolverFlags,
    /// Also write animation.svg: the disk rolling on the magnified beam (beam scenes).
    #[arg(long)]
    animate: bool,
    /// Write summary.yaml and history.csv only, no SVG figures (sweeps of single runs, where
    /// drawing costs more than the run).
    #[arg(long)]
    no_figures: bool,
}

pub fn run(args: RunArgs) -> Result<(), Error> {
    let RunArgs {
        scene,
        out,
        solver,
        animate,
        no_figures,
    } = args;
    if animate && no_figures {
        return Err(Error::Input(
            "--animate draws a figure, which --no-figures leaves out; give one of them".into(),
        ));
    }
    // A planned sweep's case runs into its plan folder, once.
    let case = crate::workflows::sweep::cluster::planned_case(&scene);
    if let Some((plan, id)) = &case {
        if solver.given() {
            return Err(Error::Input(format!(
                "{} is a planned case, which carries its solver settings; run it without --method, --rtol or --atol",
                scene.display()
            )));
        }
        crate::workflows::sweep::cluster::check_case(plan, id)?;
        if crate::workflows::sweep::cluster::is_done(plan, id) {
            say!("{}: case {id} is done already; skipped", plan.display());
            return Ok(());
        }
    }
    let path = scene;
    let scene = Scene::load(&path)?;
    if animate && scene.beam().is_none() {
        return Err(Error::Input(
            "--animate draws a beam scene; a rigid curve's positions are drawn in track.svg".into(),
        ));
    }
    let over = Overrides {
        animate,
        ..solver.overrides(&scene)?
    };
    let result = run::run(&scene, &over, true)?;
    let dir = out.unwrap_or_else(|| match &case {
        Some((plan, id)) => plan.join("runs").join(id),
        None => Path::new("out").join(&scene.name),
    });
    output::write_all(&result, &dir, !no_figures)?;
    if let (true, Run::Beam(b)) = (animate, &result) {
        output::animation::write_animation(b, &dir.join("animation.svg"))?;
    }
    if let Some((plan, id)) = &case {
        crate::workflows::sweep::cluster::record_case(plan, id, &result)?;
    }
    tell(&scene.name, &result);
    say!("  wrote {}", dir.display());
    Ok(())
}

/// What the run did, on the terminal: how it ended, where the disk or the probes went, the
/// energy balance and the solver's work.
fn tell(name: &str, result: &Run) {
    let h = result.header();
    let disk = match &result {
        Run::Beam(b) if b.setup.disks.len() > 1 => b
            .stopped_disk
            .map_or("a disk".to_string(), |k| b.setup.disk_names()[k].clone()),
        _ => "the disk".to_string(),
    };
    let lost = match &result {
        Run::Beam(b) => b
            .vehicles
            .iter()
            .find_map(|v| v.lost_contact.as_ref().map(|a| (v.name.clone(), a.clone()))),
        Run::Rolling(_) => None,
    };
    match lost {
        Some((vehicle, axle)) => say!(
            "{}: the wheel of axle {axle} of vehicle {vehicle} lost contact with the deck at t = {:.6} s (its contact force fell to zero; contact-lost): a disk wheel (`wheel: disk`) on an axle with mass flies and lands instead",
            name,
            h.t_end
        ),
        None => say!("{}: {}", name, h.stop.sentence(&disk, h.t_end)),
    }
    match &result {
        Run::Rolling(r) => {
            let d = &r.last.disk;
            say!("  disk at s = {:.6}, centre ({:.6}, {:.6}) m, velocity ({:.6}, {:.6}) m/s, Ω = {:.6} 1/s", d.s, d.x, d.y, d.vx, d.vy, d.omega);
        }
        Run::Beam(b) => {
            for (p, [_, w, ..]) in b.setup.probes.iter().zip(&b.extremes.probes) {
                say!(
                    "  probe {} (x = {} m): w from {:.6e} to {:.6e} m",
                    p.name,
                    p.x,
                    w.min,
                    w.max
                );
            }
            for v in &b.vehicles {
                for (body, a, _) in v.bodies.iter().filter(|(_, a, _)| a.seen()) {
                    say!(
                        "  vehicle {} body {}: largest |a| {:.6e} m/s² at t = {:.6} s",
                        v.name,
                        body,
                        a.largest_magnitude().0,
                        a.largest_magnitude().1
                    );
                }
            }
            for w in b.warnings() {
                say!("  warning: {w}");
            }
        }
    }
    say!("  energy drift {:.2e} (relative)", h.energy.max_rel_drift());
    let s = &h.stats;
    say!(
        "  {} rtol {} atol {}: {} steps, {} rejected, {} rhs evaluations, {} Jacobians, {} factorisations, {:.3} s",
        h.method.name(), output::tolerance(h.rtol), output::tolerance(h.atol), s.steps, s.rejected, s.rhs_evals, s.jacobians, s.factorizations, s.wall_s
    );
}
