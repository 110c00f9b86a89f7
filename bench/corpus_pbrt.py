#!/usr/bin/env python3
"""What bench/corpus.sh needs to know of, and do to, a pbrt-v4 scene file (standard library only).

  corpus_pbrt.py top WIDTH FILE...    prints "FILE<tab>HEIGHT" for those FILEs that are whole
                                      scenes (have WorldBegin): HEIGHT is the Film's aspect at
                                      WIDTH pixels
  corpus_pbrt.py hash FILE            prints a SHA-256 of FILE and of every file it Includes or
                                      Imports, recursively, and of the size and time of each file
                                      their string parameters name (the key of pbrt-v4's cached
                                      renders)
  corpus_pbrt.py rewrite FILE W H DIR writes DIR/<FILE's name>: FILE with its Film at W x H
                                      (no crop window or file name, "rgb" for a gbuffer or
                                      spectral film) and every other entry of FILE's
                                      folder linked into DIR, so that its relative paths resolve
                                      as they did (pbrt-v4 has no resolution flag)

pbrt-v4's scene format: directives are capitalised words; each takes a parameter list of
"type name" strings followed by a value or a bracketed list of values; '#' starts a comment.
"""
import gzip
import hashlib
import os
import re
import sys

TOKEN = re.compile(r'#[^\n]*|"[^"]*"|\[|\]|[^\s"\[\]#]+')


def read_text(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:2] == b"\x1f\x8b":
        data = gzip.decompress(data)
    return data.decode("utf-8", errors="replace")


def tokens(text):
    """(kind, text, start, end) for each token; comments are left out."""
    for m in TOKEN.finditer(text):
        t = m.group(0)
        if t.startswith("#"):
            continue
        kind = "string" if t.startswith('"') else ("bracket" if t in "[]" else "word")
        yield kind, t, m.start(), m.end()


def is_directive(tok):
    return tok[0] == "word" and tok[1][:1].isupper() and tok[1].isalpha()


def directives(text):
    """(name, first_argument_tokens, params, start, end): params maps "type name" to its value
    tokens; start and end span the whole directive in text."""
    toks = list(tokens(text))
    i = 0
    while i < len(toks):
        if not is_directive(toks[i]):
            i += 1
            continue
        name, start = toks[i][1], toks[i][2]
        j = i + 1
        args = []
        # Leading arguments: a type string (Film "rgb") or numbers (LookAt, Scale ...).
        while j < len(toks) and not is_directive(toks[j]):
            if toks[j][0] == "string" and len(toks[j][1].split()) == 2:
                break  # the first "type name" of the parameter list
            args.append(toks[j])
            j += 1
        params = {}
        while j < len(toks) and toks[j][0] == "string" and len(toks[j][1].split()) == 2:
            key = " ".join(toks[j][1].strip('"').split())
            j += 1
            values = []
            if j < len(toks) and toks[j][1] == "[":
                j += 1
                while j < len(toks) and toks[j][1] != "]":
                    values.append(toks[j])
                    j += 1
                j += 1
            elif j < len(toks):
                values.append(toks[j])
                j += 1
            params[key] = values
        end = toks[j - 1][3] if j > i + 1 else toks[i][3]
        yield name, args, params, start, end
        i = j


def param(params, name):
    """The values of parameter `name` whatever its type, or None."""
    for key, values in params.items():
        if key.split()[1] == name:
            return [v[1].strip('"') for v in values]
    return None


def film_of(text):
    for name, args, params, start, end in directives(text):
        if name == "Film":
            return args, params, start, end
        if name == "WorldBegin":
            break
    return None


def film_height(text, width):
    film = film_of(text)
    params = film[1] if film else {}
    x = param(params, "xresolution")
    y = param(params, "yresolution")
    x, y = (float(x[0]) if x else 1280), (float(y[0]) if y else 720)
    return max(1, round(int(width) * y / x))


def references(folder, text):
    """The files text Includes or Imports, and those its string parameters name (meshes, images,
    spectra), resolved against folder (the top file's, as pbrt-v4 resolves them)."""
    for name, args, params, start, end in directives(text):
        if name in ("Include", "Import") and args and args[0][0] == "string":
            yield "scene", os.path.join(folder, args[0][1].strip('"'))
        for key, values in params.items():
            if key.split()[0] == "string":
                for value in values:
                    candidate = os.path.join(folder, value[1].strip('"'))
                    if value[0] == "string" and os.path.isfile(candidate):
                        yield "data", candidate


def command_hash(path):
    """Scene files by content; the data files they name (often large) by size and time."""
    digest = hashlib.sha256()
    folder = os.path.dirname(os.path.abspath(path))
    seen = set()
    pending = [("scene", os.path.abspath(path))]
    while pending:
        kind, current = pending.pop(0)
        if current in seen:
            continue
        seen.add(current)
        if kind == "data":
            info = os.stat(current)
            digest.update(("%s\0%d %d\n" % (current, info.st_size, info.st_mtime_ns)).encode())
            continue
        try:
            with open(current, "rb") as f:
                data = f.read()
        except OSError:
            digest.update(current.encode() + b"\0(missing)\n")
            continue
        digest.update(current.encode() + b"\0" + hashlib.sha256(data).digest())
        pending.extend(references(folder, read_text(current)))
    print(digest.hexdigest())


def command_top(width, paths):
    for path in paths:
        try:
            text = read_text(path)
        except OSError:
            continue
        if any(name == "WorldBegin" for name, *_ in directives(text)):
            print("%s\t%d" % (path, film_height(text, width)))


def command_rewrite(path, width, height, out_dir):
    text = read_text(path)
    keep = []
    film = film_of(text)
    film_type = "rgb"
    if film:
        args, params, start, end = film
        if args and args[0][1].strip('"') not in ("gbuffer", "spectral"):
            film_type = args[0][1].strip('"')
        for key, values in params.items():
            if key.split()[1] in ("xresolution", "yresolution", "cropwindow", "pixelbounds",
                                  "coordinatesystem",  # gbuffer's
                                  "filename"):
                continue
            keep.append('"%s" [ %s ]' % (key, " ".join(v[1] for v in values)))
    new_film = 'Film "%s" "integer xresolution" [ %d ] "integer yresolution" [ %d ] %s\n' % (
        film_type, int(width), int(height), " ".join(keep))
    if film:
        text = text[:film[2]] + new_film + text[film[3]:]
    else:
        world = re.search(r"^\s*WorldBegin", text, re.M)
        text = text[:world.start()] + "\n" + new_film + text[world.start():]
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(out_dir, exist_ok=True)
    for entry in os.listdir(folder):
        if entry != os.path.basename(path):
            os.symlink(os.path.join(folder, entry), os.path.join(out_dir, entry))
    with open(os.path.join(out_dir, os.path.basename(path)), "w") as f:
        f.write(text)


def main(argv):
    if len(argv) >= 3 and argv[1] == "top":
        command_top(argv[2], argv[3:])
    elif len(argv) == 3 and argv[1] == "hash":
        command_hash(argv[2])
    elif len(argv) == 6 and argv[1] == "rewrite":
        command_rewrite(*argv[2:])
    else:
        sys.stderr.write(__doc__)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
