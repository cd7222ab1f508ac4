//! `tumble study [FILE...] [--format table|csv|json] [--svg PATH] [--response NAME[,NAME…]]`:
//! what accuracy costs in time.
//!
//! Without files, the built-in scenes ([`crate::study::scenes`]). A FILE (or a bundled lesson's
//! name) runs for its own `duration` ([`crate::study::DEFAULT_DURATION`] without one); its
//! reference is exact for one free body (no joint, spring, obstacle or drag); with joints,
//! springs, drag or several bodies it is the same model stepped by `rk4` at a tenth of the
//! smallest swept step, checked by halving it ([`crate::study::reference`]); with contact
//! `rk4` at a tenth of the smallest swept step — the output says which. A FILE with `[[cloth]]` is a cloth case ([`crate::study::cloth`]): the particle
//! integrators over a ladder of dt around the sheets' explicit limit, against a converged
//! `symplectic-euler` reference. `--response A,B,…` also charts those contact methods on every
//! case with contact, each over the dt sweep at the scene's integrator
//! ([`crate::study::methods`]).

use super::{response_named, Failure};
use crate::study::{self, report, Case, Config};
use std::path::PathBuf;

/// Output formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// A table per scene, sorted by cost, frontier marked, one sentence per scene.
    Table,
    /// Raw numbers, one row per run.
    Csv,
    /// Everything, including the sentences and fitted orders.
    Json,
}

#[derive(Debug, clap::Args)]
pub struct StudyArgs {
    /// Scene files (default: the built-in scenes).
    pub files: Vec<PathBuf>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    pub format: Format,
    /// Also write a log–log SVG plot of error against cost to PATH.
    #[arg(long, value_name = "PATH")]
    pub svg: Option<PathBuf>,
    /// Collision response of the scenes with contact (overrides `contact.response`); a comma
    /// list (`impulse,soft-step`) also charts those methods against each other, each over
    /// the dt sweep at the scene's integrator (the first one is the scene's response).
    #[arg(long, value_name = "NAME[,NAME…]")]
    pub response: Option<String>,
}

/// `--response NAME[,NAME…]`: the names, each a response (the error of an unknown one is
/// `--response NAME`'s), none empty and none twice.
pub fn response_list(text: &str) -> Result<Vec<String>, Failure> {
    let names: Vec<String> = text.split(',').map(|n| n.trim().to_string()).collect();
    for (i, name) in names.iter().enumerate() {
        if name.is_empty() {
            return Err(Failure::bad_input(format!(
                "--response `{text}`: an empty name in the list (write names separated by commas, \
                 e.g. `impulse,soft-step`)"
            )));
        }
        response_named(name)?;
        if names[..i].contains(name) {
            return Err(Failure::bad_input(format!(
                "--response `{text}`: `{name}` is listed twice"
            )));
        }
    }
    Ok(names)
}

/// The cases: the built-in scenes, or the files (with their own durations); `response`
/// (one name, or the first of a list) replaces the collision response of every case with
/// contact (a file without contact is an error, as with `tumble run --response`).
pub fn cases(files: &[PathBuf], response: Option<&str>) -> Result<Vec<Case>, Failure> {
    let names = response.map(response_list).transpose()?;
    let response = names.as_ref().map(|n| n[0].as_str());
    let overrides = super::Overrides {
        response: response.map(str::to_string),
        ..super::Overrides::default()
    };
    if files.is_empty() {
        let mut cases = Vec::new();
        for mut case in study::scenes::builtin() {
            // A built-in scene without contact keeps its own settings.
            if case.scene.contact.is_some() {
                let path = PathBuf::from(&case.name);
                super::apply(&path, &mut case.scene, &overrides)?;
            }
            cases.push(case);
        }
        return Ok(cases);
    }
    files
        .iter()
        .map(|path| {
            let lesson = super::load_with(path, &overrides)?;
            Ok(Case::from_lesson(&lesson))
        })
        .collect()
}

/// `--svg PATH` can be written: its folder exists (checked before the study runs, which takes
/// seconds).
fn check_svg_path(path: &std::path::Path) -> Result<(), Failure> {
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => std::path::Path::new("."),
    };
    if path.is_dir() {
        return Err(Failure::bad_input(format!(
            "--svg {}: is a directory, not a file to write",
            path.display()
        )));
    }
    if !folder.is_dir() {
        return Err(Failure::bad_input(format!(
            "--svg {}: no such folder `{}`",
            path.display(),
            folder.display()
        )));
    }
    Ok(())
}

/// The methods each case's chart compares (`--response A,B,…`, two names or more): per case
/// with contact, the responses named, each passing the scene's rules as `--response` would
/// (the scene's own `soft-step` keys kept when it names `soft-step`); None for a case
/// without contact and for one name or none.
fn methods(
    cases: &[Case],
    files: &[PathBuf],
    response: Option<&str>,
) -> Result<Vec<Option<Vec<crate::physics::Response>>>, Failure> {
    let names = response.map(response_list).transpose()?.unwrap_or_default();
    cases
        .iter()
        .zip(files.iter().map(Some).chain(std::iter::repeat(None)))
        .map(|(case, file)| {
            let contact = case.scene.contact.is_some() && !case.scene.obstacles.is_empty();
            if names.len() < 2 || !contact {
                return Ok(None);
            }
            let path = file.cloned().unwrap_or_else(|| PathBuf::from(&case.name));
            names
                .iter()
                .map(|name| {
                    let mut scene = case.scene.clone();
                    let overrides = super::Overrides {
                        response: Some(name.clone()),
                        ..super::Overrides::default()
                    };
                    super::apply(&path, &mut scene, &overrides)?;
                    Ok(scene.contact.map(|m| m.response))
                })
                .collect::<Result<Option<Vec<_>>, Failure>>()
        })
        .collect()
}

/// Runs the study and prints it.
pub fn study(args: &StudyArgs) -> Result<(), Failure> {
    if let Some(path) = &args.svg {
        check_svg_path(path)?;
    }
    let cases = cases(&args.files, args.response.as_deref())?;
    let methods = methods(&cases, &args.files, args.response.as_deref())?;
    let config = Config::default();
    for (case, path) in cases
        .iter()
        .zip(args.files.iter().map(Some).chain(std::iter::repeat(None)))
    {
        study::check_work(case, &config).map_err(|why| {
            let at = path.map_or_else(|| case.name.clone(), |p| p.display().to_string());
            Failure::bad_input(format!("{at}: {why}"))
        })?;
    }
    let started = std::time::Instant::now();
    let mut studies = study::study(&cases, &config, &mut |_, _| {});
    for ((study, case), methods) in studies.iter_mut().zip(&cases).zip(&methods) {
        if let Some(methods) = methods {
            study.methods = Some(study::methods::study(
                case,
                methods,
                &config.dts,
                config.timing,
            ));
        }
    }
    let elapsed = started.elapsed().as_secs_f64();
    let text = match args.format {
        Format::Table => format!(
            "{}study: {} runs in {elapsed:.1} s (ns/step: the minimum of up to {} timed runs after \
             a warm-up, each the median of its 1000-step chunks)\n",
            report::table(&studies),
            studies
                .iter()
                .map(|s| s.rows.len()
                    + s.cloth.as_ref().map_or(0, |c| c.rows.len())
                    + s.methods.as_ref().map_or(0, |m| m.rows.len()))
                .sum::<usize>(),
            config.timing.repeats
        ),
        Format::Csv => report::csv(&studies),
        Format::Json => report::json(&studies),
    };
    // Scene names and titles come from files: their control characters escaped.
    let text = text
        .split('\n')
        .map(crate::scene::printable)
        .collect::<Vec<_>>()
        .join("\n");
    super::output::print(&text)?;
    if let Some(path) = &args.svg {
        study::plot::svg(&studies, path).map_err(Failure::bad_input)?;
    }
    Ok(())
}
