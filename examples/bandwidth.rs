//! What one core of this machine reads and writes per second, for buffers of a frame's sizes:
//! the floor under a frame that moves so many bytes (see DEVELOPERS.md, "The two speed targets
//! still open"). Best of 40 passes each: a sum of every float (read), a fill (write), and
//! `b = a + 1` (read and write, both counted).
//!
//!     cargo run --release --example bandwidth -- [MB ...]     (default: 2 16 64 256)
use std::hint::black_box;
use std::time::Instant;

fn main() {
    let sizes: Vec<usize> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let sizes = if sizes.is_empty() { vec![2, 16, 64, 256] } else { sizes };
    println!("| MB | read GB/s | write GB/s | read + write GB/s |");
    println!("|---|---|---|---|");
    for mb in sizes {
        let n = mb << 18; // floats
        let a = vec![1.0f32; n];
        let mut b = vec![1.0f32; n];
        let (mut read, mut write, mut both) = (f64::MAX, f64::MAX, f64::MAX);
        for _ in 0..40 {
            let t = Instant::now();
            let sum = a.chunks_exact(16).fold([0.0f32; 16], |mut s, c| {
                s.iter_mut().zip(c).for_each(|(s, x)| *s += x);
                s
            });
            black_box(sum);
            read = read.min(t.elapsed().as_secs_f64());
            let t = Instant::now();
            b.fill(black_box(2.0));
            black_box(&mut b);
            write = write.min(t.elapsed().as_secs_f64());
            let t = Instant::now();
            b.iter_mut().zip(&a).for_each(|(b, a)| *b = a + 1.0);
            black_box(&mut b);
            both = both.min(t.elapsed().as_secs_f64());
        }
        let bytes = (4 * n) as f64;
        let rate = |seconds: f64, bytes: f64| bytes / seconds / 1e9;
        println!(
            "| {mb} | {:.1} | {:.1} | {:.1} |",
            rate(read, bytes),
            rate(write, bytes),
            rate(both, 2.0 * bytes)
        );
    }
}
