use std::io::Write;

fn main() {
    let cli = capstan::cli::Cli::parse_with_help();
    match capstan::cli::run(cli) {
        Ok(out) => {
            // A closed pipe (e.g. `| head`) is not an error worth a panic.
            let _ = writeln!(std::io::stdout().lock(), "{out}");
        }
        Err(e) => {
            if let Some(out) = e.stdout() {
                let _ = writeln!(std::io::stdout().lock(), "{out}");
            }
            eprintln!("error: {e}");
            std::process::exit(e.exit_code());
        }
    }
}
