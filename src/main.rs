//! The `rollbeam` command line: run, check, static, modes, studies.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use rollbeam::beam::Beam;
use rollbeam::error::Error;
use rollbeam::ode::Method;
use rollbeam::run::{self, Overrides, Run};
use rollbeam::scene::{method_names, BeamScene, BeamStart, Model, Scene};
use rollbeam::{output, say, studies, sweep, tradeoff};

#[derive(Parser)]
#[command(
    name = "rollbeam",
    version,
    about = "A rigid disk rolling without slip on a rigid curve or a Reissner beam"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run one scene and write summary.yaml, history.csv and figures.
    Run {
        scene: PathBuf,
        /// Output folder (default out/<scene name>).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Integrator: dopri5, trbdf2, esdirk4 or genalpha (beam scenes).
        #[arg(long)]
        method: Option<String>,
        #[arg(long, allow_negative_numbers = true)]
        rtol: Option<f64>,
        #[arg(long, allow_negative_numbers = true)]
        atol: Option<f64>,
        /// Also write animation.svg: the disk rolling on the magnified beam (beam scenes).
        #[arg(long)]
        animate: bool,
    },
    /// Validate a scene and print the model it would build; runs nothing.
    Check { scene: PathBuf },
    /// Static equilibrium of a beam scene.
    Static {
        scene: PathBuf,
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Natural frequencies and mode shapes of a beam scene.
    Modes {
        scene: PathBuf,
        #[arg(long)]
        count: Option<usize>,
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Run one scene over a range of one parameter, in parallel on all cores; writes
    /// sweep.csv (one row per run) and sweep.svg.
    Sweep {
        scene: PathBuf,
        /// KEY=FROM:TO:COUNT, e.g. disk.omega0=-10:-120:111 (any number the scene holds).
        #[arg(long = "set")]
        set: String,
        /// Output folder (default out/<scene name>-sweep).
        #[arg(long)]
        out: Option<PathBuf>,
        #[arg(long)]
        method: Option<String>,
        #[arg(long, allow_negative_numbers = true)]
        rtol: Option<f64>,
        #[arg(long, allow_negative_numbers = true)]
        atol: Option<f64>,
    },
    /// Work–precision of a scene: every method over a range of tolerances (and meshes, on a
    /// beam) against a converged reference; writes tradeoff.csv, tradeoff.svg and
    /// tradeoff.txt, and names the cheapest settings for 1e-2, 1e-4 and 1e-6.
    Tradeoff {
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
        /// Steps a run may take before it gives up (default 20000 on a beam, 200000 on a curve).
        #[arg(long)]
        max_steps: Option<usize>,
    },
    /// Rerun every scene under studies/ and regenerate the report's figures.
    Studies {
        /// Folder for the runs (default out).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Leave out the work–precision diagrams: about 51 of the job's 52 minutes on two cores.
        #[arg(long)]
        no_work_precision: bool,
    },
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(
                e.kind(),
                ErrorKind::DisplayHelp
                    | ErrorKind::DisplayVersion
                    | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
            ) {
                let _ = e.print();
                return ExitCode::SUCCESS;
            }
            // clap's message spans several lines; keep the part before its usage block.
            let text = e.to_string();
            let sentence: Vec<&str> = text
                .lines()
                .map(str::trim)
                .take_while(|l| !l.is_empty() && !l.starts_with("Usage:"))
                .collect();
            eprintln!(
                "rollbeam: {} (see rollbeam --help)",
                sentence.join(" ").trim_start_matches("error: ")
            );
            return ExitCode::from(1);
        }
    };
    match dispatch(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("rollbeam: {e}");
            ExitCode::from(e.exit_code() as u8)
        }
    }
}

fn positive(value: Option<f64>, flag: &str) -> Result<Option<f64>, Error> {
    match value {
        Some(v) if !(v > 0.0 && v.is_finite()) => Err(Error::Input(format!(
            "{flag} must be a positive number (got {v})"
        ))),
        v => Ok(v),
    }
}

fn dispatch(command: Command) -> Result<(), Error> {
    match command {
        Command::Run {
            scene,
            out,
            method,
            rtol,
            atol,
            animate,
        } => {
            let scene = Scene::load(&scene)?;
            if animate && scene.beam().is_none() {
                return Err(Error::Input(
                    "--animate draws a beam scene; a rigid curve's positions are drawn in track.svg".into(),
                ));
            }
            let method = method.map(|m| parse_method(&m, &scene)).transpose()?;
            let over = Overrides {
                method,
                rtol: positive(rtol, "--rtol")?,
                atol: positive(atol, "--atol")?,
                fixed_step: None,
                ..Default::default()
            };
            let result = run::run(&scene, &over, true)?;
            let dir = out.unwrap_or_else(|| Path::new("out").join(&scene.name));
            output::write_all(&result, &dir)?;
            if let (true, Run::Beam(b)) = (animate, &result) {
                output::animation::write_animation(b, &dir.join("animation.svg"))?;
            }
            say!("{}: {}", scene.name, result.stop().sentence(result.t_end()));
            match &result {
                Run::Rolling(r) => {
                    let d = &r.last.disk;
                    say!("  disk at s = {:.6}, centre ({:.6}, {:.6}) m, velocity ({:.6}, {:.6}) m/s, Ω = {:.6} 1/s", d.s, d.x, d.y, d.vx, d.vy, d.omega);
                }
                Run::Beam(b) => {
                    for (k, p) in b.setup.probes.iter().enumerate() {
                        let (lo, hi) = b
                            .rows
                            .iter()
                            .map(|r| r.probes[k].w)
                            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, c), w| {
                                (a.min(w), c.max(w))
                            });
                        say!(
                            "  probe {} (x = {} m): w from {lo:.6e} to {hi:.6e} m",
                            p.name,
                            p.x
                        );
                    }
                }
            }
            say!(
                "  energy drift {:.2e} (relative)",
                result.energy().max_rel_drift()
            );
            let s = result.stats();
            let (m, rt, at) = match &result {
                Run::Rolling(r) => (r.method, r.rtol, r.atol),
                Run::Beam(b) => (b.method, b.rtol, b.atol),
            };
            say!(
                "  {} rtol {} atol {}: {} steps, {} rejected, {} rhs evaluations, {} Jacobians, {} factorisations, {:.3} s",
                m.name(), output::tolerance(rt), output::tolerance(at), s.steps, s.rejected, s.rhs_evals, s.jacobians, s.factorizations, s.wall_s
            );
            say!("  wrote {}", dir.display());
            Ok(())
        }
        Command::Check { scene } => {
            let scene = Scene::load(&scene)?;
            say!("scene {}: valid", scene.name);
            match &scene.model {
                Model::Rolling(setup) => {
                    let r = &setup.rolling;
                    say!(
                        "  track: rigid {} curve{}",
                        r.curve.kind(),
                        r.curve
                            .domain()
                            .map_or(String::new(), |(a, b)| format!(", s in [{a}, {b}]"))
                    );
                    say!(
                        "  disk: m = {} kg, a = {} m, C = {} kg m², s0 = {}, Ω0 = {} 1/s{}",
                        r.disk.mass,
                        r.disk.radius,
                        r.disk.inertia(),
                        r.s0,
                        r.omega0,
                        r.mu.map_or(String::new(), |m| format!(", mu = {m}"))
                    );
                    say!(
                        "  model: {} formulation, {} unknowns (no beam)",
                        setup.formulation.name(),
                        run::model(setup).initial_state().len()
                    );
                }
                Model::Beam(setup) => {
                    let b = Beam::new(setup.beam.clone());
                    let spec = &b.spec;
                    say!(
                        "  track: Reissner beam, L = {:.6} m at {:.4}° , supports {} / {}{}, starting {}",
                        b.length,
                        b.angle.to_degrees(),
                        spec.supports[0].name(),
                        spec.supports[1].name(),
                        if spec.bearings.is_empty() {
                            String::new()
                        } else {
                            format!(", bearings holding w at x = {:?}", spec.bearings)
                        },
                        match setup.start {
                            BeamStart::Rest => "undeformed at rest",
                            BeamStart::Static => "at rest in static equilibrium",
                        }
                    );
                    say!(
                        "  mesh: {} elements of degree {}, {} quadrature, {} beam unknowns",
                        spec.elements,
                        spec.order,
                        spec.quadrature.name(),
                        b.dim()
                    );
                    if let Some(d) = &setup.discretisation {
                        say!("  chosen for accuracy {:e}: {}", d.accuracy, d.why);
                    }
                    match &setup.disk {
                        None => say!("  disk: none (no disk unknowns)"),
                        Some(d) => say!(
                            "  disk: m = {} kg, a = {} m, s0 = {}, Ω0 = {} 1/s, {} coupling ({}), contact patch ±{} m{}",
                            d.disk.mass,
                            d.disk.radius,
                            d.s0,
                            d.omega0,
                            d.coupling.name(),
                            if d.coupling.rolls() {
                                "1 more unknown: the contact point s"
                            } else {
                                "prescribed travel, no disk unknowns"
                            },
                            d.patch,
                            d.mu.map_or(String::new(), |m| format!(", mu = {m}"))
                        ),
                    }
                    say!(
                        "  loads: {}, probes: {}",
                        setup.loads.len(),
                        setup
                            .probes
                            .iter()
                            .map(|p| format!("{} at x = {}", p.name, p.x))
                            .collect::<Vec<_>>()
                            .join(", ")
                    );
                }
            }
            if scene.solver.rtol_from_accuracy {
                if let Some(b) = scene.beam() {
                    let (rtol, why) = rollbeam::analysis::discretisation::rtol_for(b);
                    say!(
                        "  rtol chosen for accuracy {:e}: {}, {why}",
                        b.accuracy,
                        output::tolerance(rtol)
                    );
                    if scene.solver.atol_scale.is_some() {
                        if let Some((atol, why)) =
                            rollbeam::analysis::discretisation::atol_for(b, rtol)
                        {
                            say!("  atol chosen with it: {}, {why}", output::tolerance(atol));
                        }
                    }
                }
            }
            say!(
                "  solver: {} rtol {} atol {}; duration {} s, output every {} s",
                scene.solver.method.name(),
                output::tolerance(scene.solver.rtol),
                output::tolerance(scene.solver.atol),
                scene.duration,
                scene.interval
            );
            Ok(())
        }
        Command::Static { scene: path, out } => {
            let scene = Scene::load(&path)?;
            let setup = beam_only(&scene, &path, "static")?;
            let dir = out.unwrap_or_else(|| Path::new("out").join(&scene.name));
            let result = rollbeam::analysis::report::statics(&scene, setup, &dir)?;
            print!("{result}");
            Ok(())
        }
        Command::Modes {
            scene: path,
            count,
            out,
        } => {
            let scene = Scene::load(&path)?;
            let setup = beam_only(&scene, &path, "modes")?;
            let dir = out.unwrap_or_else(|| Path::new("out").join(&scene.name));
            let result =
                rollbeam::analysis::report::modes(&scene, setup, count.unwrap_or(6), &dir)?;
            print!("{result}");
            Ok(())
        }
        Command::Sweep {
            scene: path,
            set,
            out,
            method,
            rtol,
            atol,
        } => {
            let scene = Scene::load(&path)?;
            let setting = sweep::Setting::parse(&set)?;
            let method = method.map(|m| parse_method(&m, &scene)).transpose()?;
            let over = Overrides {
                method,
                rtol: positive(rtol, "--rtol")?,
                atol: positive(atol, "--atol")?,
                fixed_step: None,
                ..Default::default()
            };
            let text = std::fs::read_to_string(&path).map_err(|e| {
                Error::Input(format!("cannot read scene file {}: {e}", path.display()))
            })?;
            let stem = path
                .file_stem()
                .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
            let rows = sweep::run_sweep(
                &text,
                &path.display().to_string(),
                &stem,
                &setting,
                &over,
                true,
            )?;
            let dir = out.unwrap_or_else(|| Path::new("out").join(format!("{}-sweep", scene.name)));
            sweep::write_sweep(&rows, &setting, &dir)?;
            let failed = rows.iter().filter(|r| r.outcome.is_err()).count();
            say!(
                "{}: {} runs over {} from {} to {}, {} failed; wrote {}",
                scene.name,
                rows.len(),
                setting.key,
                setting.from,
                setting.to,
                failed,
                dir.display()
            );
            Ok(())
        }
        Command::Tradeoff {
            scene: path,
            out,
            methods,
            rtols,
            elements,
            max_steps,
        } => {
            let scene = Scene::load(&path)?;
            let mut plan = tradeoff::Plan::default_for(&scene);
            if !methods.is_empty() {
                plan.methods = methods
                    .iter()
                    .map(|m| parse_method(m, &scene))
                    .collect::<Result<_, _>>()?;
            }
            if !rtols.is_empty() {
                for &r in &rtols {
                    positive(Some(r), "--rtols")?;
                }
                plan.rtols = rtols;
            }
            if !elements.is_empty() {
                if scene.beam().is_none() {
                    return Err(Error::Input(
                        "--elements meshes a beam; this scene has a rigid curve".into(),
                    ));
                }
                if let Some(&bad) = elements.iter().find(|&&n| n == 0 || n > 1000) {
                    return Err(Error::Input(format!(
                        "--elements {bad}: an element count is from 1 to 1000"
                    )));
                }
                plan.meshes = elements;
            }
            if let Some(m) = max_steps {
                if m == 0 {
                    return Err(Error::Input("--max-steps must be at least 1".into()));
                }
                plan.max_steps = m;
            }
            say!("{}: computing the reference…", scene.name);
            let reference = tradeoff::reference(&scene, &plan)?;
            let trials = tradeoff::trials(&scene, &plan, &reference, true);
            let dir =
                out.unwrap_or_else(|| Path::new("out").join(format!("{}-tradeoff", scene.name)));
            for line in tradeoff::write_tradeoff(&scene, &reference, &trials, &dir)? {
                say!("  {line}");
            }
            say!("  wrote {}", dir.display());
            Ok(())
        }
        Command::Studies {
            out,
            no_work_precision,
        } => {
            let root = Path::new(env!("CARGO_MANIFEST_DIR"));
            let here = if Path::new("studies").is_dir() {
                Path::new(".")
            } else {
                root
            };
            let out = out.unwrap_or_else(|| here.join("out"));
            studies::run_all(
                &here.join("studies"),
                &out,
                &here.join("report").join("figures"),
                !no_work_precision,
            )?;
            Ok(())
        }
    }
}

/// A method named on the command line that can integrate this scene.
fn parse_method(name: &str, scene: &Scene) -> Result<Method, Error> {
    let m = Method::from_name(name).ok_or_else(|| {
        Error::Input(format!(
            "--method '{name}' is unknown; use one of {}",
            method_names()
        ))
    })?;
    if m == Method::GenAlpha && scene.beam().is_none() {
        return Err(Error::Input("--method genalpha integrates beam scenes; use dopri5, trbdf2 or esdirk4 for a rigid curve".into()));
    }
    Ok(m)
}

fn beam_only<'a>(scene: &'a Scene, path: &Path, command: &str) -> Result<&'a BeamScene, Error> {
    scene.beam().ok_or_else(|| {
        Error::Input(format!(
            "{}: `{command}` needs a beam track; this scene has a rigid curve",
            path.display()
        ))
    })
}
