//! Scene files: the example loads; malformed input is reported with the file
//! and the line or field, never a panic.

mod common;

use common::Scratch;
use std::path::{Path, PathBuf};
use wobble::scene::Scene;
use wobble::scene::mesh::Mesh;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn error(dir: &Path, text: &str, name: &str) -> String {
    Scene::load(&write(dir, name, text))
        .unwrap_err()
        .to_string()
}

#[test]
fn example_scene_loads() {
    let s = Scene::load(&root().join("fixtures/scenes/example.toml")).unwrap();
    assert_eq!(s.objects.len(), 3);
    assert_eq!(s.fog.map(|f| (f.near, f.far)), Some((1500.0, 4000.0)));
    assert_eq!(s.textures[0].texture.clut.len(), 16);
    // The pyramid: a quad base and four triangles.
    assert_eq!(s.meshes[0].mesh.faces.len(), 5);
    assert_eq!(s.meshes[0].mesh.triangle_count(), 6);
}

#[test]
fn syntax_error_names_file_and_line() {
    let scratch = Scratch::new("syntax_error_names_file_and_line");
    let e = error(
        &scratch,
        "[screen]\nwidth = 320\nheight = \n",
        "syntax.toml",
    );
    assert!(e.contains("syntax.toml") && e.contains("line 3"), "{e}");
}

#[test]
fn unknown_field_is_named() {
    let scratch = Scratch::new("unknown_field_is_named");
    let e = error(&scratch, "[camera]\nfov = 90\n", "field.toml");
    assert!(e.contains("field.toml") && e.contains("fov"), "{e}");
}

#[test]
fn bad_values_are_refused() {
    let scratch = Scratch::new("bad_values_are_refused");
    let e = error(&scratch, "[screen]\nwidth = 300\n", "w.toml");
    assert!(e.contains("screen.width"), "{e}");
    let e = error(
        &scratch,
        "[[mesh]]\nname = \"c\"\nbuiltin = \"cube\"\n[[object]]\nmesh = \"c\"\ntessellation = 9\n",
        "t.toml",
    );
    assert!(e.contains("tessellation"), "{e}");
    let e = error(&scratch, "[[object]]\nmesh = \"nothing\"\n", "m.toml");
    assert!(e.contains("no mesh named `nothing`"), "{e}");
}

/// A missing OBJ: the message names the file as resolved against the scene's directory and
/// the operating system's reason.
#[test]
fn missing_obj_names_the_file() {
    let scratch = Scratch::new("missing_obj_names_the_file");
    let e = error(
        &scratch,
        "[[mesh]]\nname = \"a\"\nfile = \"does-not-exist.obj\"\n",
        "obj.toml",
    );
    let resolved = scratch.join("does-not-exist.obj");
    assert!(
        e.contains(&format!("mesh file {}", resolved.display())),
        "{e}"
    );
    assert!(e.contains("No such file or directory"), "{e}");
}

/// A missing texture PNG: the same.
#[test]
fn missing_texture_names_the_file_and_the_reason() {
    let scratch = Scratch::new("missing_texture_names_the_file_and_the_reason");
    let e = error(
        &scratch,
        "[[texture]]\nname = \"t\"\nfile = \"gone.png\"\n",
        "tex.toml",
    );
    assert!(e.contains("texture file ") && e.contains("gone.png"), "{e}");
    assert!(e.contains("No such file or directory"), "{e}");
}

#[test]
fn mesh_too_large_reports_the_scale_needed() {
    let scratch = Scratch::new("mesh_too_large_reports_the_scale_needed");
    // The cube's coordinates reach 1.0; scale 40000 exceeds 32767 and 32767 is the limit.
    let e = error(
        &scratch,
        "[[mesh]]\nname = \"c\"\nbuiltin = \"cube\"\n[[object]]\nmesh = \"c\"\nscale = 40000\n",
        "big.toml",
    );
    assert!(e.ends_with("use scale <= 32767"), "{e}");
}

#[test]
fn oversized_png_is_refused() {
    let scratch = Scratch::new("oversized_png_is_refused");
    // A 300x10 PNG: wider than a texture page.
    let img = image::RgbImage::new(300, 10);
    let png = write(&scratch, "wide.png", "");
    img.save(&png).unwrap();
    let scene = format!(
        "[[texture]]\nname = \"t\"\nfile = \"{}\"\n",
        png.file_name().unwrap().to_str().unwrap()
    );
    let e = error(&scratch, &scene, "wide.toml");
    assert!(e.contains("wide.png") && e.contains("300x10"), "{e}");
}

#[test]
fn malformed_obj_names_file_and_line() {
    let scratch = Scratch::new("malformed_obj_names_file_and_line");
    let obj = write(
        &scratch,
        "broken.obj",
        "# a triangle with a bad index\nv 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 7\n",
    );
    let e = Mesh::load_obj(&obj).unwrap_err().to_string();
    assert!(e.contains("broken.obj") && e.contains("line 6"), "{e}");
    let obj = write(&scratch, "badv.obj", "v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n");
    let e = Mesh::load_obj(&obj).unwrap_err().to_string();
    assert!(e.contains("badv.obj") && e.contains("line 2"), "{e}");
}

/// The `[accuracy]` table sets the non-hardware knobs; unknown values are refused.
#[test]
fn accuracy_table() {
    let scratch = Scratch::new("accuracy_table");
    let s = Scene::load(&write(
        &scratch,
        "acc.toml",
        "[accuracy]\ndivide = \"exact\"\nsubpixel = true\nperspective_uv = true\n",
    ))
    .unwrap();
    assert_eq!(s.accuracy.divide, gte::DivideMode::Exact);
    assert!(s.accuracy.subpixel && s.accuracy.perspective_uv);
    let d = Scene::load(&write(&scratch, "acc0.toml", "")).unwrap();
    assert_eq!(
        d.accuracy,
        wobble::scene::Accuracy::default(),
        "hardware by default"
    );
    let e = error(&scratch, "[accuracy]\ndivide = \"fast\"\n", "acc1.toml");
    assert!(e.contains("acc1.toml") && e.contains("fast"), "{e}");
}

/// Every float field is checked, and the error names the field as written in the file.
#[test]
fn every_float_field_is_validated_by_name() {
    let scratch = Scratch::new("every_float_field_is_validated_by_name");
    let object = "[[mesh]]\nname = \"c\"\nbuiltin = \"cube\"\n[[object]]\nmesh = \"c\"\n";
    let cases: [(String, &str); 14] = [
        ("[light]\ndirection = [0, 0, 0]\n".into(), "light.direction"),
        (
            "[light]\ndirection = [nan, 1, 0]\n".into(),
            "light.direction[0]",
        ),
        (
            "[light]\ndirection = [1, inf, 0]\n".into(),
            "light.direction[1]",
        ),
        (
            "[light]\ndirection = [1, 0, 1e308]\n".into(),
            "light.direction[2]",
        ),
        (
            "[camera]\nposition = [0, nan, 0]\n".into(),
            "camera.position[1]",
        ),
        (
            "[camera]\nrotation = [0, 0, -inf]\n".into(),
            "camera.rotation[2]",
        ),
        ("[fog]\nnear = nan\n".into(), "fog.near"),
        ("[fog]\nfar = inf\n".into(), "fog.far"),
        (
            format!("{object}position = [1e308, 0, 0]\n"),
            "object 1: position[0]",
        ),
        (
            format!("{object}rotation = [0, nan, 0]\n"),
            "object 1: rotation[1]",
        ),
        (format!("{object}spin = [0, 0, inf]\n"), "object 1: spin[2]"),
        (format!("{object}scale = nan\n"), "object 1: scale"),
        (format!("{object}scale = 0\n"), "object 1: scale"),
        (format!("{object}scale = 1e308\n"), "object 1: scale"),
    ];
    for (i, (text, field)) in cases.iter().enumerate() {
        let e = error(&scratch, text, &format!("num{i}.toml"));
        assert!(
            e.contains(&format!("num{i}.toml: {field} must be")),
            "case {i} ({field}): {e}"
        );
    }
    // Neighbouring valid values still load.
    Scene::load(&write(
        &scratch,
        "num-ok.toml",
        "[light]\ndirection = [0, 0, 0.001]\n[camera]\nposition = [0, 0, -1000000]\n",
    ))
    .unwrap();
}

/// A non-finite number in `v`, `vt` or `vn` is refused with the file's own line number.
#[test]
fn non_finite_obj_numbers_name_the_line() {
    let scratch = Scratch::new("non_finite_obj_numbers_name_the_line");
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    let cases = [
        (
            format!("# a comment\n\nv 1 2 3\nv nan 0 0\n{tri}f 2 3 4\n"),
            "line 4",
            "`v`",
        ),
        (
            format!("{tri}vt 0 0\nvt inf 0\nf 1/1 2/2 3/1\n"),
            "line 5",
            "`vt`",
        ),
        (
            format!("{tri}vn 0 0 1\nvn 0 -inf 0\nf 1//1 2//2 3//1\n"),
            "line 5",
            "`vn`",
        ),
        // Beyond f32: the reader would hold infinity.
        (format!("{tri}v 1e39 0 0\nf 1 2 4\n"), "line 4", "`v`"),
    ];
    for (i, (text, line, keyword)) in cases.iter().enumerate() {
        let obj = write(&scratch, &format!("nf{i}.obj"), text);
        let e = Mesh::load_obj(&obj).unwrap_err().to_string();
        assert!(
            e.contains(&format!("nf{i}.obj: {line}: {keyword}")) && e.contains("not finite"),
            "case {i}: {e}"
        );
    }
}

/// Coordinates far too large for any sensible scale are said so plainly, without
/// 31-digit numbers or a suggested scale of 0.000000.
#[test]
fn huge_obj_coordinates_are_reported_plainly() {
    let scratch = Scratch::new("huge_obj_coordinates_are_reported_plainly");
    let obj = write(
        &scratch,
        "huge.obj",
        "v 0 0 0\nv 1e30 0 0\nv 0 1 0\nf 1 2 3\n",
    );
    let scene = "[[mesh]]\nname = \"h\"\nfile = \"huge.obj\"\n[[object]]\nmesh = \"h\"\n";
    assert!(obj.exists());
    let e = error(&scratch, scene, "huge.toml");
    assert!(e.contains("far too large") && e.contains("1.0e30"), "{e}");
    assert!(!e.contains("0.000000") && !e.contains("000000000"), "{e}");
}

/// A frame with more polygons than the per-frame cap: the stats say the cap was reached
/// and the message names the cap and how to stay under it.
#[test]
fn polygon_cap_is_named() {
    use wobble::pipeline::{MAX_POLYGONS, PipelineOptions, Renderer, cap_message};
    use wobble::scene::mesh::{MeshFace, MeshVertex};
    use wobble::scene::{MeshAsset, Object};
    // One small quad facing the camera (at z = -1000 looking +Z), repeated past the cap.
    let v = |x: f64, y: f64| MeshVertex {
        position: [x, y, 0.0],
        normal: [0.0, 0.0, -1.0],
        uv: [0.0, 0.0],
    };
    let face = MeshFace {
        indices: [0, 1, 2, 3],
        quad: true,
    };
    let count = MAX_POLYGONS + 1000;
    let mesh = Mesh {
        vertices: vec![v(-1.0, -1.0), v(1.0, -1.0), v(-1.0, 1.0), v(1.0, 1.0)],
        faces: vec![face; count],
    };
    let mut scene = Scene::default_scene();
    scene.textures.clear();
    scene.light = None;
    scene.fog = None;
    scene.camera.position = [0.0, 0.0, -1000.0];
    scene.camera.rotation = [0.0; 3];
    scene.meshes = vec![MeshAsset {
        name: "many".into(),
        mesh,
    }];
    scene.objects = vec![Object {
        mesh: 0,
        texture: None,
        position: [0.0; 3],
        rotation: [0.0; 3],
        spin: [0.0; 3],
        scale: 5.0,
        color: [128, 128, 128],
        blend: None,
        tessellation: 0,
        split_extent: wobble::scene::DEFAULT_SPLIT_EXTENT,
    }];
    let mut r = Renderer::new(scene.clone(), PipelineOptions::default()).unwrap();
    let stats = r.render_frame(0);
    assert_eq!(stats.drawn, MAX_POLYGONS);
    assert_eq!(stats.dropped, 1000);
    assert_eq!(stats.capped, 1);
    let m = cap_message(&stats).unwrap();
    assert!(
        m.contains("cap of 131072 polygons") && m.contains("tessellation"),
        "{m}"
    );
    // Under the cap: nothing said.
    scene.meshes[0].mesh.faces.truncate(10);
    let mut r = Renderer::new(scene, PipelineOptions::default()).unwrap();
    let stats = r.render_frame(0);
    assert_eq!((stats.drawn, stats.capped), (10, 0));
    assert_eq!(cap_message(&stats), None);
}

/// The example scene is a room, not a floating slab: its floor runs under the camera, so the
/// bottom row of the picture is floor, not the background colour of the sky (the top-left
/// pixel).
#[test]
fn example_floor_reaches_the_bottom_of_the_screen() {
    use wobble::pipeline::{PipelineOptions, Renderer};
    let s = Scene::load(&root().join("fixtures/scenes/example.toml")).unwrap();
    let mut r = Renderer::new(s, PipelineOptions::default()).unwrap();
    r.render_frame(0);
    let img = r.image();
    let sky = *img.get_pixel(0, 0);
    let bottom = img.height() - 1;
    let background = (0..img.width())
        .filter(|&x| *img.get_pixel(x, bottom) == sky)
        .count();
    assert_eq!(
        background, 0,
        "{background} background pixels on the bottom row"
    );
}
