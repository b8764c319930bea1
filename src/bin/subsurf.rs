//! `subsurf --scheme catmull-clark --levels N [--boundary MODE] INPUT.obj -o OUTPUT.obj`
//!
//! OpenSubdiv `t` tags in the OBJ (creases, corners, holes, `interpolateboundary`,
//! `creasemethod`, `smoothtriangles`) are used unless `--ignore-tags`; `--boundary` and
//! `--crease-method` override the file's `interpolateboundary` and `creasemethod`. Texture
//! coordinates (`vt`, `f v/vt`) are refined as a face-varying channel (`--fvar-linear` says where
//! they stay linear) and written to the output, unless `--ignore-uv`. `--limit` moves the
//! result to the limit surface and writes its normals (`vn`); `--normals` writes the normals
//! alone.

use std::process::ExitCode;
use std::time::Instant;
use subsurf::evaluator::subdivide_closed;
use subsurf::io::{read_obj_with, write_obj_to, ObjReadOptions};
use subsurf::scheme::{Boundary, Options, Scheme};
use subsurf::{CreaseMethod, FVarLinear, HalfEdgeMesh};

const USAGE: &str = "usage: subsurf --scheme SCHEME --levels N [--boundary MODE] [--crease-method M] [--ignore-tags]
               [--fvar-linear MODE] [--ignore-uv] [--limit] [--normals]
               [--max-faces N] [--max-bytes N] [--stats]
               INPUT.obj [-o OUTPUT.obj]

  --scheme SCHEME    catmull-clark (default), loop, doo-sabin, quad-triangle, sqrt3,
                     bilinear, midpoint;
                     or a comma-separated list, one scheme per level
  --levels N         levels of subdivision, 0 or more (default 1, or the list's length)
  --boundary MODE    edge-and-corner, edge-only, fixed, average, none (catmull-clark, loop,
                     doo-sabin); default: the file's 'interpolateboundary' tag, else
                     edge-and-corner
  --crease-method M  uniform or chaikin; default: the file's 'creasemethod' tag, else uniform
  --ignore-tags      ignore the file's OpenSubdiv 't' tags (creases, corners, holes, ...)
  --fvar-linear MODE where the file's texture coordinates (vt) stay linear: none,
                     corners-only, corners-plus1 (default), corners-plus2, boundaries, all
                     (OpenSubdiv's FVarLinearInterpolation)
  --ignore-uv        ignore the file's texture coordinates; the output has none
  --limit            move the points and texture coordinates to the limit surface
                     (last level catmull-clark, loop or quad-triangle; bilinear and
                     midpoint points stay) and write one normal per vertex (vn)
  --normals          write one normal per vertex (vn) without moving the points: limit
                     normals after catmull-clark, loop and quad-triangle, from the faces
                     after the other schemes
  --max-faces N      refuse when the result would have more faces (default 16777216)
  --max-bytes N      refuse when the result's arrays would take more bytes (default 1073741824)
  --stats            print counts and timings to stderr
  -o OUTPUT.obj      where to write the result (default: standard output)";

struct Args {
    schemes: Vec<Scheme>,
    boundary: Option<Boundary>,
    crease_method: Option<CreaseMethod>,
    ignore_tags: bool,
    fvar_linear: FVarLinear,
    ignore_uv: bool,
    limit: bool,
    normals: bool,
    max_faces: u64,
    max_bytes: u64,
    stats: bool,
    input: String,
    output: Option<String>,
}

fn parse_args(args: &[String]) -> Result<Args, String> {
    let mut parsed = Args {
        schemes: vec![Scheme::CatmullClark],
        boundary: None,
        crease_method: None,
        ignore_tags: false,
        fvar_linear: FVarLinear::default(),
        ignore_uv: false,
        limit: false,
        normals: false,
        max_faces: subsurf::scheme::DEFAULT_MAX_FACES,
        max_bytes: subsurf::scheme::DEFAULT_MAX_BYTES,
        stats: false,
        input: String::new(),
        output: None,
    };
    let mut input = None;
    let mut levels: Option<u32> = None;
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        let mut value =
            |flag: &str| it.next().cloned().ok_or_else(|| format!("{flag} needs a value"));
        match arg.as_str() {
            "--scheme" => {
                parsed.schemes =
                    Scheme::parse_list(&value("--scheme")?).map_err(|e| format!("{e}"))?
            }
            "--levels" => {
                let v = value("--levels")?;
                let n: u32 = v.parse().map_err(|_| {
                    format!("--levels '{v}' is not a whole number of levels (0, 1, 2, ...)")
                })?;
                let max = subsurf::scheme::MAX_LEVELS;
                if n as usize > max {
                    return Err(format!("--levels {n} is more than the {max} subsurf accepts"));
                }
                levels = Some(n);
            }
            "--boundary" => {
                parsed.boundary = Some(value("--boundary")?.parse().map_err(|e| format!("{e}"))?)
            }
            "--crease-method" => {
                parsed.crease_method =
                    Some(value("--crease-method")?.parse().map_err(|e| format!("{e}"))?)
            }
            "--ignore-tags" => parsed.ignore_tags = true,
            "--fvar-linear" => {
                parsed.fvar_linear = value("--fvar-linear")?.parse().map_err(|e| format!("{e}"))?
            }
            "--ignore-uv" => parsed.ignore_uv = true,
            "--limit" => parsed.limit = true,
            "--normals" => parsed.normals = true,
            "--max-bytes" => {
                let v = value("--max-bytes")?;
                parsed.max_bytes =
                    v.parse().map_err(|_| format!("--max-bytes '{v}' is not a whole number"))?;
            }
            "--max-faces" => {
                let v = value("--max-faces")?;
                parsed.max_faces =
                    v.parse().map_err(|_| format!("--max-faces '{v}' is not a whole number"))?;
            }
            "--stats" => parsed.stats = true,
            "-o" | "--output" => parsed.output = Some(value("-o")?),
            "-h" | "--help" => return Err(String::new()),
            flag if flag.starts_with('-') && flag.len() > 1 => {
                return Err(format!("unknown option '{flag}'"));
            }
            path => {
                if input.replace(path.to_string()).is_some() {
                    return Err(format!("more than one input file given ('{path}')"));
                }
            }
        }
    }
    parsed.input = input.ok_or("no input file given")?;
    match (parsed.schemes.as_slice(), levels) {
        ([one], levels) => parsed.schemes = vec![*one; levels.unwrap_or(1) as usize],
        (list, Some(n)) if n as usize != list.len() => {
            return Err(format!(
                "--scheme lists {} schemes but --levels is {n}; give one scheme per level, or leave out --levels",
                list.len()
            ));
        }
        _ => {}
    }
    Ok(parsed)
}

fn run(args: Args) -> Result<(), String> {
    let start = Instant::now();
    let text = std::fs::read_to_string(&args.input)
        .map_err(|e| format!("cannot read '{}': {e}", args.input))?;
    let at = |e: subsurf::Error| format!("{}: {e}", args.input);
    let parts = ObjReadOptions { tags: !args.ignore_tags, uv: !args.ignore_uv };
    let obj = read_obj_with(&text, parts).map_err(at)?;
    let (input, mut tags, file_boundary) = (obj.mesh, obj.tags, obj.boundary);
    let attributes = obj.attributes;
    if let Some(method) = args.crease_method {
        tags.crease_method = method;
    }
    let boundary = args.boundary.or(file_boundary).unwrap_or_default();
    let read_time = start.elapsed();

    let t = Instant::now();
    let mesh = HalfEdgeMesh::from_poly(&input).map_err(|e| format!("{}: {e}", args.input))?;
    let build_time = t.elapsed();
    let options = Options {
        schemes: args.schemes.clone(),
        boundary,
        max_faces: args.max_faces,
        max_bytes: args.max_bytes,
        fvar_linear: args.fvar_linear,
        limit: args.limit,
        normals: args.limit || args.normals,
    };
    let (in_v, in_e, in_f) = (mesh.num_vertices(), mesh.num_edges(), mesh.num_cells());
    let t = Instant::now();
    // Tangents are not written, so the closed forms may give the limit and its normals.
    let refine = |channels| {
        let closed = subdivide_closed(&mesh, channels, &options, &tags).transpose();
        closed
            .unwrap_or_else(|| {
                subsurf::scheme::subdivide_mesh_borrowed_with(&mesh, channels, &options, &tags)
            })
            .map(|mut refined| (refined.take_normals(), refined.into_parts()))
    };
    let (normals, (output, channels)) = refine(&attributes).map_err(|e| e.to_string())?;
    let refine_time = t.elapsed();

    let t = Instant::now();
    // Written as it is made: the text of a large result is several times its arrays' size.
    let write = |out: &mut dyn std::io::Write, target: &str| {
        write_obj_to(out, &output, &channels, normals.as_deref()).map_err(|e| match e {
            subsurf::Error::Io(message) => format!("cannot write {target}: {message}"),
            e => e.to_string(),
        })
    };
    match &args.output {
        Some(path) => {
            let mut file =
                std::fs::File::create(path).map_err(|e| format!("cannot write '{path}': {e}"))?;
            write(&mut file, &format!("'{path}'"))?
        }
        None => write(&mut std::io::stdout().lock(), "to standard output")?,
    }
    let write_time = t.elapsed();
    if args.stats {
        let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
        let names: Vec<&str> = args.schemes.iter().map(|s| s.name()).collect();
        eprintln!("schemes     {} ({boundary} boundary)", names.join(","));
        eprintln!(
            "tags        {} creases, {} corners, {} holes ({} creases)",
            tags.creases.len(),
            tags.corners.len(),
            tags.holes.len(),
            tags.crease_method
        );
        eprintln!("input       {in_v} vertices, {in_e} edges, {in_f} faces");
        eprintln!("output      {} vertices, {} faces", output.num_vertices(), output.num_faces());
        for (before, after) in attributes.iter().zip(&channels) {
            eprintln!(
                "{:<11} {} values in, {} out ({} linear)",
                after.name,
                before.len(),
                after.len(),
                args.fvar_linear
            );
        }
        eprintln!("read        {:.3} ms", ms(read_time));
        eprintln!("build       {:.3} ms", ms(build_time));
        eprintln!("subdivide   {:.3} ms", ms(refine_time));
        eprintln!("write       {:.3} ms", ms(write_time));
        let rate = output.num_faces() as f64 / (build_time + refine_time).as_secs_f64();
        eprintln!("throughput  {:.1} M output faces/s (build + subdivide)", rate / 1e6);
    }
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match parse_args(&args) {
        Err(message) if message.is_empty() => {
            println!("{USAGE}");
            ExitCode::SUCCESS
        }
        Err(message) => {
            eprintln!("subsurf: {message}\n\n{USAGE}");
            ExitCode::from(2)
        }
        Ok(args) => match run(args) {
            Ok(()) => ExitCode::SUCCESS,
            Err(message) => {
                eprintln!("subsurf: {message}");
                ExitCode::FAILURE
            }
        },
    }
}
