//! Scene files: the example loads; malformed input is reported with the file
//! and the line or field, never a panic.

use std::path::PathBuf;
use wobble::scene::Scene;
use wobble::scene::mesh::Mesh;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn write(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("wobble-scene-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn error(text: &str, name: &str) -> String {
    Scene::load(&write(name, text)).unwrap_err().to_string()
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
    let e = error("[screen]\nwidth = 320\nheight = \n", "syntax.toml");
    assert!(e.contains("syntax.toml") && e.contains("line 3"), "{e}");
}

#[test]
fn unknown_field_is_named() {
    let e = error("[camera]\nfov = 90\n", "field.toml");
    assert!(e.contains("field.toml") && e.contains("fov"), "{e}");
}

#[test]
fn bad_values_are_refused() {
    let e = error("[screen]\nwidth = 300\n", "w.toml");
    assert!(e.contains("screen.width"), "{e}");
    let e = error(
        "[[mesh]]\nname = \"c\"\nbuiltin = \"cube\"\n[[object]]\nmesh = \"c\"\ntessellation = 9\n",
        "t.toml",
    );
    assert!(e.contains("tessellation"), "{e}");
    let e = error("[[object]]\nmesh = \"nothing\"\n", "m.toml");
    assert!(e.contains("no mesh named `nothing`"), "{e}");
}

#[test]
fn missing_obj_names_the_file() {
    let e = error(
        "[[mesh]]\nname = \"a\"\nfile = \"does-not-exist.obj\"\n",
        "obj.toml",
    );
    assert!(e.contains("does-not-exist.obj"), "{e}");
}

#[test]
fn mesh_too_large_reports_the_scale_needed() {
    // The cube's coordinates reach 1.0; scale 40000 exceeds 32767 and 32767 is the limit.
    let e = error(
        "[[mesh]]\nname = \"c\"\nbuiltin = \"cube\"\n[[object]]\nmesh = \"c\"\nscale = 40000\n",
        "big.toml",
    );
    assert!(e.contains("use scale <= 32767.000000"), "{e}");
}

#[test]
fn oversized_png_is_refused() {
    // A 300x10 PNG: wider than a texture page.
    let img = image::RgbImage::new(300, 10);
    let png = write("wide.png", "");
    img.save(&png).unwrap();
    let scene = format!(
        "[[texture]]\nname = \"t\"\nfile = \"{}\"\n",
        png.file_name().unwrap().to_str().unwrap()
    );
    let e = error(&scene, "wide.toml");
    assert!(e.contains("wide.png") && e.contains("300x10"), "{e}");
}

#[test]
fn malformed_obj_names_file_and_line() {
    let obj = write(
        "broken.obj",
        "# a triangle with a bad index\nv 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 7\n",
    );
    let e = Mesh::load_obj(&obj).unwrap_err().to_string();
    assert!(e.contains("broken.obj") && e.contains("line 6"), "{e}");
    let obj = write("badv.obj", "v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n");
    let e = Mesh::load_obj(&obj).unwrap_err().to_string();
    assert!(e.contains("badv.obj") && e.contains("line 2"), "{e}");
}

/// The `[accuracy]` table sets the non-hardware knobs; unknown values are refused.
#[test]
fn accuracy_table() {
    let s = Scene::load(&write(
        "acc.toml",
        "[accuracy]\ndivide = \"exact\"\nsubpixel = true\nperspective_uv = true\n",
    ))
    .unwrap();
    assert_eq!(s.accuracy.divide, wobble::scene::Divide::Exact);
    assert!(s.accuracy.subpixel && s.accuracy.perspective_uv);
    let d = Scene::load(&write("acc0.toml", "")).unwrap();
    assert_eq!(
        d.accuracy,
        wobble::scene::Accuracy::default(),
        "hardware by default"
    );
    let e = error("[accuracy]\ndivide = \"fast\"\n", "acc1.toml");
    assert!(e.contains("acc1.toml") && e.contains("fast"), "{e}");
}
