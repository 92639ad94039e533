use clap::Parser;

fn main() {
    let cli = capstan::cli::Cli::parse();
    match capstan::cli::run(cli) {
        Ok(out) => println!("{out}"),
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(e.exit_code());
        }
    }
}
