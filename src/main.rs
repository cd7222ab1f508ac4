//! `tumble`: the command line and the terminal app.

fn main() -> std::process::ExitCode {
    tumble::cli::main()
}
