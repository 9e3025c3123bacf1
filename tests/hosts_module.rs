//! fortran-shim/jointlin.f90 against include/jointlin.h: every constant, struct and
//! function of the header is in the Fortran module with the same value, components,
//! argument names and interoperable types (mapping rules: the module's header comment),
//! and nothing else is bound. Then both are compiled and the struct sizes compared.

mod hosts_common;

use std::collections::BTreeMap;
use std::process::Command;

use hosts_common::{root, run_ok, scratch};

/// A C declaration reduced to what the Fortran side must match.
#[derive(Debug, Clone, PartialEq)]
struct Arg {
    name: String,
    /// Fortran base type, e.g. `integer(c_int32_t)`, `type(jointlin_contact)`.
    base: String,
    by_value: bool,
    /// Pointer to const (Fortran intent(in)).
    read_only: bool,
    dims: Option<String>,
}

#[derive(Debug, Default)]
struct Api {
    constants: BTreeMap<String, i64>,
    structs: BTreeMap<String, Vec<Arg>>,
    /// name -> (result base type or None for void, arguments)
    functions: BTreeMap<String, (Option<String>, Vec<Arg>)>,
}

fn strip_c_comments(s: &str) -> String {
    let mut out = String::new();
    let mut rest = s;
    while let Some(i) = rest.find("/*") {
        out.push_str(&rest[..i]);
        let j = rest[i..].find("*/").expect("closed comment");
        rest = &rest[i + j + 2..];
    }
    out.push_str(rest);
    out.lines()
        .map(|l| l.split("//").next().unwrap())
        .filter(|l| !l.trim_start().starts_with('#'))
        .collect::<Vec<_>>()
        .join("\n")
}

fn c_scalar(t: &str) -> Option<&'static str> {
    Some(match t {
        "int32_t" | "uint32_t" => "integer(c_int32_t)",
        "int64_t" => "integer(c_int64_t)",
        "size_t" => "integer(c_size_t)",
        "double" => "real(c_double)",
        "char" => "character(kind=c_char)",
        _ => return None,
    })
}

/// `const struct jointlin_contact *contact` -> Arg, by the module's mapping rules.
fn c_arg(decl: &str, component: bool) -> Arg {
    let decl = decl.trim();
    let (decl, dims) = match decl.find('[') {
        Some(i) => (&decl[..i], Some(decl[i + 1..decl.len() - 1].to_string())),
        None => (decl, None),
    };
    let name_start = decl
        .rfind(|c: char| !(c.is_alphanumeric() || c == '_'))
        .map_or(0, |i| i + 1);
    let name = decl[name_start..].to_string();
    let ty = decl[..name_start].trim();
    let stars = ty.matches('*').count();
    let read_only = ty.starts_with("const ");
    let core = ty
        .trim_start_matches("const ")
        .trim_end_matches(['*', ' '])
        .trim_start_matches("struct ")
        .trim();
    let (base, by_value) = match (core, stars) {
        ("jointlin_store", 1) => ("type(c_ptr)".to_string(), true),
        ("jointlin_store", 2) => ("type(c_ptr)".to_string(), false),
        ("char", 1) if component => ("type(c_ptr)".to_string(), false),
        (t, n) => {
            let base = c_scalar(t)
                .map(str::to_string)
                .unwrap_or_else(|| format!("type({t})"));
            (base, n == 0)
        }
    };
    Arg {
        name,
        base,
        by_value: by_value && !component,
        read_only: read_only && stars > 0 && !component,
        dims,
    }
}

fn parse_header(text: &str) -> Api {
    let mut api = Api::default();
    for line in text.lines() {
        let mut it = line.split_whitespace();
        if it.next() == Some("#define") {
            if let (Some(name), Some(v)) = (it.next(), it.next()) {
                api.constants.insert(name.to_string(), v.parse().unwrap());
            }
        }
    }
    let code = strip_c_comments(text);
    let mut rest = code.as_str();
    while let Some(i) = rest.find("typedef struct ") {
        let after = &rest[i + "typedef struct ".len()..];
        let name: String = after
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        let body_start = after.find('{');
        let semi = after.find(';').unwrap();
        if let Some(b) = body_start.filter(|&b| b < semi) {
            let end = after.find('}').unwrap();
            let fields = after[b + 1..end]
                .split(';')
                .filter(|f| !f.trim().is_empty())
                .map(|f| c_arg(f, true))
                .collect();
            api.structs.insert(name, fields);
            rest = &after[end..];
        } else {
            rest = &after[semi..]; // opaque
        }
    }
    let functions = code.split("extern \"C\" {").nth(1).expect("extern C block");
    for proto in functions.split(';') {
        let Some(open) = proto.find('(') else {
            continue;
        };
        let head = proto[..open].trim();
        let name_start = head.rfind([' ', '*']).unwrap() + 1;
        let name = head[name_start..].to_string();
        let ret = head[..name_start].trim();
        let result = (ret != "void").then(|| {
            if ret.contains('*') {
                "type(c_ptr)".to_string() // const char *: a static C string
            } else {
                c_scalar(ret).unwrap().to_string()
            }
        });
        let inner = &proto[open + 1..proto.rfind(')').unwrap()];
        let args = if inner.trim() == "void" {
            vec![]
        } else {
            inner.split(',').map(|a| c_arg(a, false)).collect()
        };
        api.functions.insert(name, (result, args));
    }
    api
}

/// Free-form statements, lower case, comments and continuations removed.
fn fortran_statements(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur = String::new();
    for line in text.lines() {
        let line = line.split('!').next().unwrap().trim().to_lowercase();
        let line = line.trim_start_matches('&').trim();
        if let Some(part) = line.strip_suffix('&') {
            cur.push_str(part);
            cur.push(' ');
        } else {
            cur.push_str(line);
            if !cur.trim().is_empty() {
                out.push(cur.split_whitespace().collect::<Vec<_>>().join(" "));
            }
            cur.clear();
        }
    }
    out
}

/// Splits at commas outside parentheses.
fn split_top(s: &str) -> Vec<String> {
    let (mut depth, mut parts, mut cur) = (0, Vec::new(), String::new());
    for c in s.chars() {
        match c {
            '(' => depth += 1,
            ')' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(cur.trim().to_string());
                cur.clear();
                continue;
            }
            _ => {}
        }
        cur.push(c);
    }
    parts.push(cur.trim().to_string());
    parts
}

/// `real(c_double), intent(in) :: a(2), b` -> one Arg per name (+ attributes).
fn fortran_decl(stmt: &str) -> Vec<(Arg, Vec<String>)> {
    let (left, right) = stmt.split_once("::").unwrap();
    let mut spec = split_top(left);
    let base = spec.remove(0).replace(' ', "");
    let by_value = spec.iter().any(|a| a == "value");
    let read_only = spec.iter().any(|a| a.replace(' ', "") == "intent(in)");
    split_top(right)
        .into_iter()
        .map(|n| {
            let n = n.split('=').next().unwrap().trim().to_string();
            let (name, dims) = match n.find('(') {
                Some(i) => (
                    n[..i].trim().to_string(),
                    Some(n[i + 1..n.len() - 1].to_string()),
                ),
                None => (n, None),
            };
            let arg = Arg {
                name,
                base: base.clone(),
                by_value,
                read_only,
                dims,
            };
            (arg, spec.clone())
        })
        .collect()
}

fn parse_module(text: &str) -> Api {
    let mut api = Api::default();
    let stmts = fortran_statements(text);
    let mut i = 0;
    while i < stmts.len() {
        let s = &stmts[i];
        if s.contains(":: jointlin_") && s.contains("parameter") {
            let (_, rhs) = s.split_once("::").unwrap();
            let (name, value) = rhs.split_once('=').unwrap();
            api.constants.insert(
                name.trim().to_uppercase(),
                value.trim().parse().expect("integer constant"),
            );
        } else if s.starts_with("type, bind(c) ::") {
            let name = s.rsplit(' ').next().unwrap().to_string();
            let mut fields = Vec::new();
            i += 1;
            while !stmts[i].starts_with("end type") {
                fields.extend(fortran_decl(&stmts[i]).into_iter().map(|(a, _)| Arg {
                    by_value: false,
                    read_only: false,
                    ..a
                }));
                i += 1;
            }
            api.structs.insert(name, fields);
        } else if (s.starts_with("function ") || s.starts_with("subroutine "))
            && s.contains("bind(c")
        {
            let is_fn = s.starts_with("function ");
            let after = s.split_once(' ').unwrap().1;
            let name = after[..after.find('(').unwrap()].trim().to_string();
            let bound = s
                .split("name='")
                .nth(1)
                .unwrap()
                .split('\'')
                .next()
                .unwrap();
            assert_eq!(bound, name, "bind(C) name of {name}");
            let dummies: Vec<String> = after
                [after.find('(').unwrap() + 1..after.find(')').unwrap()]
                .split(',')
                .map(|a| a.trim().to_string())
                .filter(|a| !a.is_empty())
                .collect();
            let mut decls = BTreeMap::new();
            i += 1;
            while !stmts[i].starts_with("end function") && !stmts[i].starts_with("end subroutine") {
                if stmts[i].contains("::") && !stmts[i].starts_with("import") {
                    for (a, _) in fortran_decl(&stmts[i]) {
                        decls.insert(a.name.clone(), a);
                    }
                }
                i += 1;
            }
            let result = is_fn.then(|| decls[&name].base.clone());
            let args = dummies
                .iter()
                .map(|d| {
                    decls
                        .get(d)
                        .unwrap_or_else(|| panic!("{name}: {d} undeclared"))
                        .clone()
                })
                .collect();
            api.functions.insert(name, (result, args));
        }
        i += 1;
    }
    api
}

fn apis() -> (Api, Api) {
    let header = std::fs::read_to_string(root().join("include/jointlin.h")).unwrap();
    let module = std::fs::read_to_string(root().join("fortran-shim/jointlin.f90")).unwrap();
    (parse_header(&header), parse_module(&module))
}

#[test]
fn module_binds_every_constant_struct_and_function_of_the_header() {
    let (c, f) = apis();
    let mut c_constants = c.constants.clone();
    c_constants.remove("JOINTLIN_H");
    assert!(c_constants.len() > 40 && c.structs.len() >= 8 && c.functions.len() >= 19);
    assert_eq!(f.constants, c_constants, "constants");
    assert_eq!(
        f.structs.keys().collect::<Vec<_>>(),
        c.structs.keys().collect::<Vec<_>>(),
        "structs"
    );
    for (name, fields) in &c.structs {
        let ff = &f.structs[name];
        for (cf, mf) in fields.iter().zip(ff) {
            assert_eq!(mf, cf, "struct {name}");
        }
        assert_eq!(
            ff.len(),
            fields.len(),
            "struct {name}: number of components"
        );
    }
    assert_eq!(
        f.functions.keys().collect::<Vec<_>>(),
        c.functions.keys().collect::<Vec<_>>(),
        "functions"
    );
    for (name, (c_result, c_args)) in &c.functions {
        let (f_result, f_args) = &f.functions[name];
        assert_eq!(f_result, c_result, "{name}: result");
        assert_eq!(f_args.len(), c_args.len(), "{name}: number of arguments");
        for (ca, fa) in c_args.iter().zip(f_args) {
            let what = format!("{name}({})", ca.name);
            assert_eq!(fa.name, ca.name, "{what}: argument name");
            assert_eq!(fa.base, ca.base, "{what}: type");
            assert_eq!(fa.by_value, ca.by_value, "{what}: value vs reference");
            if !ca.by_value {
                assert_eq!(fa.read_only, ca.read_only, "{what}: intent(in) iff const");
            }
        }
    }
}

#[test]
fn the_drift_check_can_fail() {
    // The same comparison on a module with one argument type changed must differ.
    let (c, _) = apis();
    let module = std::fs::read_to_string(root().join("fortran-shim/jointlin.f90")).unwrap();
    let broken = module.replacen(
        "integer(c_int32_t), value :: mcrd",
        "integer(c_int64_t), value :: mcrd",
        1,
    );
    assert_ne!(broken, module);
    let f = parse_module(&broken);
    let name = "jointlin_store_register_point";
    assert_ne!(f.functions[name], c.functions[name]);
}

#[test]
fn struct_sizes_agree_between_gcc_and_gfortran() {
    let (c, _) = apis();
    let dir = scratch("sizes");
    let mut c_src = String::from("#include <stdio.h>\n#include \"jointlin.h\"\nint main(void) {\n");
    let mut f_src = String::from(
        "program sizes\n  use, intrinsic :: iso_c_binding, only: c_sizeof\n  use jointlin\n",
    );
    for name in c.structs.keys() {
        c_src.push_str(&format!(
            "  printf(\"{name} %zu\\n\", sizeof(struct {name}));\n"
        ));
        f_src.push_str(&format!("  type({name}) :: v_{name}\n"));
    }
    c_src.push_str("  return 0;\n}\n");
    for name in c.structs.keys() {
        f_src.push_str(&format!(
            "  write (*, '(a,1x,i0)') '{name}', c_sizeof(v_{name})\n"
        ));
    }
    f_src.push_str("end program sizes\n");
    std::fs::write(dir.join("sizes.c"), c_src).unwrap();
    std::fs::write(dir.join("sizes.f90"), f_src).unwrap();
    let include = root().join("include");
    run_ok(
        Command::new("gcc")
            .arg(format!("-I{}", include.display()))
            .args(["-o", "sizes_c", "sizes.c"])
            .current_dir(&dir),
    );
    run_ok(
        Command::new("gfortran")
            .args(["-Wall", "-c"])
            .arg(root().join("fortran-shim/jointlin.f90"))
            .current_dir(&dir),
    );
    run_ok(
        Command::new("gfortran")
            .args(["-o", "sizes_f", "sizes.f90"])
            .current_dir(&dir),
    );
    let c_out = run_ok(&mut Command::new(dir.join("sizes_c"))).stdout;
    let f_out = run_ok(&mut Command::new(dir.join("sizes_f"))).stdout;
    assert_eq!(
        String::from_utf8_lossy(&f_out),
        String::from_utf8_lossy(&c_out)
    );
}
