//! The `rollbeam` command line: parse the arguments, hand them to the subcommand, and turn
//! its error into one sentence and an exit code. The subcommands are in `src/commands/`.

use std::process::ExitCode;

use clap::{Parser, Subcommand};

use rollbeam::commands;

/// A run allocates many short-lived vectors per step and per output row (rows of the
/// rider's terms, states, stations); glibc's allocator spent about a tenth of D44's run in
/// malloc and free, mimalloc's thread-local free lists a fraction of that.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

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
    Run(commands::run::RunArgs),
    /// Validate a scene and print the model it would build; runs nothing.
    Check(commands::check::CheckArgs),
    /// Static equilibrium of a beam scene.
    Static(commands::analyses::StaticArgs),
    /// Natural frequencies and mode shapes of a beam scene.
    Modes(commands::analyses::ModesArgs),
    /// Run one scene over a range of one parameter, in parallel on all cores; writes
    /// sweep.csv (one row per run) and sweep.svg.
    Sweep(commands::sweep::SweepArgs),
    /// Work–precision of a scene: every method over a range of tolerances (and meshes, on a
    /// beam) against a converged reference; writes tradeoff.csv, tradeoff.svg and
    /// tradeoff.txt, and names the cheapest settings for 1e-2, 1e-4 and 1e-6.
    Tradeoff(commands::tradeoff::TradeoffArgs),
    /// Rerun every scene under studies/ and regenerate the report's figures.
    Studies(commands::studies::StudiesArgs),
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
    let done = match cli.command {
        Command::Run(args) => commands::run::run(args),
        Command::Check(args) => commands::check::check(args),
        Command::Static(args) => commands::analyses::static_command(args),
        Command::Modes(args) => commands::analyses::modes_command(args),
        Command::Sweep(args) => commands::sweep::sweep(args),
        Command::Tradeoff(args) => commands::tradeoff::tradeoff(args),
        Command::Studies(args) => commands::studies::studies(args),
    };
    match done {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let sentence = rollbeam::error::short_numbers(&e.to_string());
            eprintln!("rollbeam: {}", sentence.replace('\n', " "));
            ExitCode::from(e.exit_code() as u8)
        }
    }
}
