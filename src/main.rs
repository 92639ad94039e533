use std::io::Write;

/// Keeps memory freed by one solve for the next (glibc's malloc): without this, glibc returns
/// freed memory above 128 KiB to the kernel (`munmap`, heap trimming), so every build of an
/// operator faults in and zeroes fresh pages for its element blocks, geometry and factors
/// (8-10 % of a small high-order solve, docs/work-precision.md). `mallopt`:
/// `M_MMAP_THRESHOLD = 32 MiB` (glibc's largest; allocations below it come from the heap) and
/// `M_TRIM_THRESHOLD = 512 MiB` (free heap kept mapped up to that); larger allocations are
/// still mapped and unmapped on their own, so big runs keep their peak. Other platforms:
/// nothing.
fn keep_freed_memory() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        unsafe extern "C" {
            fn mallopt(param: core::ffi::c_int, value: core::ffi::c_int) -> core::ffi::c_int;
        }
        const M_TRIM_THRESHOLD: core::ffi::c_int = -1;
        const M_MMAP_THRESHOLD: core::ffi::c_int = -3;
        // SAFETY: mallopt only sets allocator parameters; called before any other thread
        // exists. A rejected value (return 0) leaves glibc's default, which is only slower.
        unsafe {
            mallopt(M_MMAP_THRESHOLD, 32 << 20);
            mallopt(M_TRIM_THRESHOLD, 512 << 20);
        }
    }
}

fn main() {
    keep_freed_memory();
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
