//! What a file may make the loaders do: how large it may be, how deep a
//! Tiled XML file may nest its elements, and how far its compressed tile
//! data may expand. A file past any of them is an error before a parser
//! sees it, never a stack overflow or memory exhausted inside one.

use std::io::Read;
use std::path::Path;

/// The largest scene, map or tileset file the loaders read, bytes
/// (64 MiB; the shipped scenes are a few kilobytes, and a CSV layer of
/// the largest tile map, 4096 × 4096, fits in about 40 MiB).
pub const MAX_FILE_BYTES: u64 = 64 << 20;

/// How deep the elements of a Tiled XML file (`.tmx`, `.tsx`, `.tx`) may
/// nest. Group layers are the only elements that nest without end (the
/// `tiled` crate reads them recursively); Tiled's own files go a few
/// levels deep.
pub const MAX_XML_DEPTH: usize = 64;

/// How many bytes the compressed (zlib or gzip) tile data of one Tiled XML
/// file may expand to, all its layers together: four bytes a cell, twice
/// the cells a CSV layer in a file of [`MAX_FILE_BYTES`] could hold (two
/// bytes a cell, `0,`), so a compressed file can ask no more of the
/// `tiled` crate than a plain one.
pub const MAX_TILE_DATA_BYTES: u64 = 4 * MAX_FILE_BYTES;

/// The bytes a Tiled map and every file it names (tilesets, templates)
/// may hold together: [`MAX_FILE_BYTES`]. Each file is read once per
/// mention (the `tiled` crate caches a tileset by the path as written), so
/// without a total a small map naming one large tileset many times read it
/// as many times.
pub const MAX_MAP_BYTES: u64 = MAX_FILE_BYTES;

/// The JSON values (numbers, strings, booleans, nulls, arrays, objects,
/// object members) a `.tmj` map and its `.tsj` tilesets may hold together:
/// a tile layer of the largest tile map, 4096 × 4096, and a million more.
/// They are counted before the text is parsed; parsed, each takes 32 bytes
/// or more, so 64 MiB of `{},` (22 million objects) took 4.4 GB.
pub const MAX_JSON_VALUES: u64 = passo_physics::MAX_TILE_CELLS as u64 + (1 << 20);

/// The tiles a tileset may say it holds (`tilecount`): the `tiled` crate
/// reserves room for that many before it reads one, so 4 294 967 295 asked
/// for 1.7 TB and aborted the process, and 30 million with an image 13.5 GB.
/// 65 536 tiles is a 4096 × 4096 image of 16-pixel tiles.
pub const MAX_TILESET_TILES: u64 = 1 << 16;

/// The objects (`<object>` elements, or JSON objects `{…}` of a `.tmj` and
/// its `.tsj` tilesets) a map file may hold. Each is built whole before any
/// check runs: 6 million `<object/>` in a `.tmx` took 2.2 GB, 8 million
/// `{}` in a `.tmj` 1.3 GB.
pub const MAX_OBJECTS: u64 = 1 << 18;

/// What one Tiled map load may still read, all its files together (see
/// [`MAX_MAP_BYTES`] and [`MAX_JSON_VALUES`]).
pub(crate) struct MapBudget {
    bytes: std::cell::Cell<u64>,
    values: std::cell::Cell<u64>,
    /// The folder every file must lie in, its links resolved (`None`: it
    /// does not exist, and no file can be read).
    root: Option<std::path::PathBuf>,
}

impl MapBudget {
    /// A budget for a map whose files must lie in `root`.
    pub(crate) fn new(root: &Path) -> Self {
        let root = if root.as_os_str().is_empty() {
            Path::new(".")
        } else {
            root
        };
        Self {
            bytes: std::cell::Cell::new(MAX_MAP_BYTES),
            values: std::cell::Cell::new(MAX_JSON_VALUES),
            root: crate::files::real_path(root).ok(),
        }
    }

    /// Checks that `path` is a regular file inside the root, before it is
    /// opened: opening a pipe would block, and a device or a file elsewhere
    /// is none of a map's business.
    pub(crate) fn check_place(&self, path: &Path) -> std::io::Result<()> {
        let refused = |why: String| std::io::Error::new(std::io::ErrorKind::PermissionDenied, why);
        if !crate::files::is_file(path)? {
            return Err(refused("is not a regular file".into()));
        }
        let real = crate::files::real_path(path)?;
        match &self.root {
            Some(root) if real.starts_with(root) => Ok(()),
            Some(root) => Err(refused(format!(
                "lies outside the map's folder {} (a scene's `root` names another)",
                root.display()
            ))),
            None => Err(refused("the map's folder does not exist".into())),
        }
    }

    /// Reads `path` whole out of what is left of the budget's bytes (and
    /// at most [`MAX_FILE_BYTES`]), if it is a regular file inside the root.
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        self.check_place(path)
            .map_err(|e| std::io::Error::new(e.kind(), format!("{}: {e}", path.display())))?;
        let left = self.bytes.get();
        let bytes = read_at_most(path, left.min(MAX_FILE_BYTES)).map_err(|e| {
            if e.kind() == std::io::ErrorKind::InvalidData && left < MAX_FILE_BYTES {
                invalid_data(format!(
                    "takes the map and the files it names past {} MiB together",
                    MAX_MAP_BYTES >> 20
                ))
            } else {
                e
            }
        })?;
        self.bytes.set(left - bytes.len() as u64);
        Ok(bytes)
    }

    /// Reads a Tiled XML file for the `tiled` crate: [`read`](Self::read),
    /// then [`check_xml`].
    pub(crate) fn read_tiled_xml(&self, path: &Path) -> std::io::Result<std::io::Cursor<Vec<u8>>> {
        let bytes = self.read(path)?;
        check_xml(&bytes).map_err(invalid_data)?;
        Ok(std::io::Cursor::new(bytes))
    }

    /// Reads a JSON file of a Tiled map as text: [`read`](Self::read), then
    /// its values counted against what is left of [`MAX_JSON_VALUES`].
    pub(crate) fn read_json(&self, path: &Path) -> std::io::Result<String> {
        let text = text(self.read(path)?)?;
        let left = self.values.get();
        let values = json_values(text.as_bytes(), left).ok_or_else(|| {
            invalid_data(format!(
                "takes the map and its tilesets past {MAX_JSON_VALUES} JSON values together, \
                 or holds more than {MAX_OBJECTS} objects"
            ))
        })?;
        self.values.set(left - values);
        Ok(text)
    }
}

/// The values in JSON text, counted without parsing it: each array and
/// object, and one more after each comma (outside strings), so every
/// element and member; `None` once past `limit`.
fn json_values(text: &[u8], limit: u64) -> Option<u64> {
    let (mut values, mut in_string, mut escaped) = (1u64, false, false);
    let mut objects = 0u64;
    for &b in text {
        if in_string {
            match (escaped, b) {
                (true, _) => escaped = false,
                (false, b'\\') => escaped = true,
                (false, b'"') => in_string = false,
                _ => {}
            }
            continue;
        }
        match b {
            b'"' => in_string = true,
            b'{' if objects == MAX_OBJECTS => return None,
            b'{' | b'[' | b',' => {
                objects += u64::from(b == b'{');
                values += 1;
                if values > limit {
                    return None;
                }
            }
            _ => {}
        }
    }
    Some(values)
}

/// Reads `path` whole, if it is at most [`MAX_FILE_BYTES`] long.
pub(crate) fn read_file(path: &Path) -> std::io::Result<Vec<u8>> {
    read_at_most(path, MAX_FILE_BYTES)
}

/// Reads `path` whole, if it is at most `limit` bytes long: never more
/// than `limit + 1` bytes are read, so a device or a pipe that never ends
/// (`/dev/zero`) is an error, not all the memory there is. (The size a
/// file's metadata gives is no bound: it is 0 for those.) After
/// [`embed_files`](crate::embed_files), it reads the embedded files.
pub fn read_at_most(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    let file = crate::files::open(path)?;
    let mut bytes = Vec::new();
    file.take(limit.saturating_add(1)).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(invalid_data(format!(
            "is larger than a file may be ({} MiB)",
            limit >> 20
        )));
    }
    Ok(bytes)
}

/// [`read_file`] as text.
pub(crate) fn read_text(path: &Path) -> std::io::Result<String> {
    text(read_file(path)?)
}

/// `bytes` as UTF-8 text, or an `InvalidData` error.
fn text(bytes: Vec<u8>) -> std::io::Result<String> {
    String::from_utf8(bytes).map_err(|e| invalid_data(e.to_string()))
}

/// An `InvalidData` error: the file is there but past a limit or malformed.
fn invalid_data(message: String) -> std::io::Error {
    std::io::Error::new(std::io::ErrorKind::InvalidData, message)
}

/// Checks a Tiled XML file against [`MAX_XML_DEPTH`] and
/// [`MAX_TILE_DATA_BYTES`]: a scan of its tags (comments, processing
/// instructions, declarations and quoted attribute values skipped) that
/// decodes the text of each `<data>` element compressed with zlib or gzip
/// and stops as soon as the total passes the limit. It also counts the
/// tiles of each layer's CSV or base64 `<data>` against the layer's
/// `width` × `height` (the `tiled` crate indexes a layer by its size and
/// panics on one whose data is shorter), and refuses infinite maps and
/// chunks, tilesets of more than [`MAX_TILESET_TILES`] tiles and more than
/// [`MAX_OBJECTS`] objects (see `check_element`). Whether the rest is a
/// valid map is the parser's business.
pub(crate) fn check_xml(bytes: &[u8]) -> Result<(), String> {
    scan(bytes, MAX_TILE_DATA_BYTES)
}

/// The `<data>` element being scanned.
struct Data {
    /// How its tiles are written (`None`: as XML elements, not counted).
    encoding: Option<Encoding>,
    /// Its depth, to find its own end tag.
    depth: usize,
    /// The cells of the layer it belongs to, as its `<layer>` tag said
    /// when it began (a `<layer>` tag inside the data does not change
    /// them).
    cells: Option<u64>,
    /// Tiles read so far.
    tiles: u64,
    /// Its first text or CDATA section has been read: the `tiled` crate
    /// decodes that one alone and ignores the rest.
    read: bool,
}

/// How a `<data>` element writes its tiles.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Encoding {
    Csv,
    Base64(Option<Compression>),
}

impl Encoding {
    /// The encoding of a `<data ...>` tag, if it is one the scan counts.
    fn of(tag: &[u8]) -> Result<Option<Self>, String> {
        Ok(match attribute(tag, b"encoding")?.as_deref() {
            Some(b"csv") => Some(Self::Csv),
            Some(b"base64") => Some(Self::Base64(Compression::of(tag)?)),
            _ => None,
        })
    }

    /// The tiles in a run of the element's text; compressed data counts
    /// against `budget` bytes of expansion, and adds to `expanded`.
    fn tiles(self, text: &[u8], budget: u64, expanded: &mut u64) -> Result<u64, String> {
        use base64::Engine;
        let text = text.trim_ascii();
        if text.is_empty() {
            return Ok(0);
        }
        let bytes = match self {
            Self::Csv => {
                let entries = text.split(|&b| b == b',');
                return Ok(entries.filter(|e| !e.trim_ascii().is_empty()).count() as u64);
            }
            Self::Base64(Some(c)) => {
                let n = c.expand(text, budget - *expanded)?;
                *expanded += n;
                n
            }
            Self::Base64(None) => base64::engine::general_purpose::STANDARD
                .decode(text)
                .map_err(|e| format!("has tile data that is not base64: {e}"))?
                .len() as u64,
        };
        // A tile is a little-endian u32.
        Ok(bytes / 4)
    }
}

/// [`check_xml`] with a budget of `budget` bytes of expanded tile data.
///
/// Names are compared by their local part (`x:data` is a `data`, as the
/// `tiled` crate reads it), attribute values are unescaped, and a `<data>`
/// lasts until its own end tag (an element inside it does not end it). Of
/// a `<data>`'s text, only its first section counts, as the `tiled` crate
/// decodes that alone: the text up to the first tag, comment or CDATA
/// section (whitespace included), or the first CDATA section if it comes
/// first. Its tiles are counted, and compressed data decoded, once.
fn scan(bytes: &[u8], budget: u64) -> Result<(), String> {
    let mut depth = 0usize;
    // The cells of the last `<layer>`, and the `<data>` being read.
    let mut cells: Option<u64> = None;
    let mut data: Option<Data> = None;
    let mut expanded = 0u64;
    let mut objects = 0u64;
    // Counts the tiles of `section` if it is the `<data>`'s first.
    let mut first = |section: &[u8], data: &mut Option<Data>| {
        if let Some(d) = data
            && !d.read
            && !section.is_empty()
        {
            d.read = true;
            if let Some(e) = d.encoding {
                d.tiles += e.tiles(section, budget, &mut expanded)?;
            }
        }
        Ok::<(), String>(())
    };
    let mut i = 0;
    while let Some(offset) = bytes[i..].iter().position(|&b| b == b'<') {
        if data.is_some() {
            first(&unescape(&bytes[i..i + offset])?, &mut data)?;
        }
        i += offset;
        let rest = &bytes[i..];
        let end = if rest.starts_with(b"<!--") {
            find(rest, b"-->")? + 3
        } else if rest.starts_with(b"<![CDATA[") {
            let end = find(rest, b"]]>")?;
            first(&rest[9..end], &mut data)?;
            end + 3
        } else if rest.starts_with(b"<?") {
            find(rest, b"?>")? + 2
        } else if rest.starts_with(b"<!") {
            tag_end(rest)? + 1
        } else if rest.starts_with(b"</") {
            if data.as_ref().is_some_and(|d| d.depth == depth) {
                let d = data.take().expect("checked");
                if let (Some(cells), Some(_)) = (d.cells, d.encoding)
                    && d.tiles < cells
                {
                    return Err(format!(
                        "has a layer of {cells} cells whose data holds {} tiles",
                        d.tiles
                    ));
                }
            }
            depth = depth.saturating_sub(1);
            tag_end(rest)? + 1
        } else {
            let end = tag_end(rest)?;
            let tag = &rest[1..end];
            let element = local(name(tag));
            if element == b"layer" {
                cells = layer_cells(tag)?;
            }
            check_element(element, tag, &mut objects)?;
            if !tag.ends_with(b"/") {
                depth += 1;
                if depth > MAX_XML_DEPTH {
                    return Err(format!("nests its elements more than {MAX_XML_DEPTH} deep"));
                }
                if data.is_none() && element == b"data" {
                    data = Some(Data {
                        encoding: Encoding::of(tag)?,
                        depth,
                        cells,
                        tiles: 0,
                        read: false,
                    });
                }
            }
            end + 1
        };
        i += end;
    }
    Ok(())
}

/// A whole-number attribute of a tag, if it has one that parses.
fn number_attribute(tag: &[u8], key: &[u8]) -> Result<Option<u64>, String> {
    let value = attribute(tag, key)?;
    Ok(value.and_then(|v| std::str::from_utf8(&v).ok()?.trim().parse().ok()))
}

/// The checks of one start tag that must come before the `tiled` crate
/// builds what it names: an infinite map (whose chunks it builds, however
/// wide, before Passo's check of the map could refuse it; a chunk at x =
/// 2^31 - 1 also overflowed inside it), a tileset's tile count, and the
/// objects counted so far.
fn check_element(element: &[u8], tag: &[u8], objects: &mut u64) -> Result<(), String> {
    let number = |key: &[u8]| number_attribute(tag, key);
    match element {
        b"map" if number(b"infinite")?.is_some_and(|n| n != 0) => {
            Err("is an infinite map: Passo loads maps of a fixed size".into())
        }
        b"chunk" => Err("has a chunk, which only an infinite map may hold".into()),
        b"tileset" => match number(b"tilecount")? {
            Some(n) if n > MAX_TILESET_TILES => Err(format!(
                "has a tileset of {n} tiles, more than {MAX_TILESET_TILES}"
            )),
            _ => Ok(()),
        },
        b"object" => {
            *objects += 1;
            if *objects > MAX_OBJECTS {
                return Err(format!("holds more than {MAX_OBJECTS} objects"));
            }
            Ok(())
        }
        _ => Ok(()),
    }
}

/// The cells of a `<layer ...>` tag, `width` × `height`, if it gives both.
fn layer_cells(tag: &[u8]) -> Result<Option<u64>, String> {
    let number = |key: &[u8]| number_attribute(tag, key);
    Ok(match (number(b"width")?, number(b"height")?) {
        (Some(w), Some(h)) => Some(u64::saturating_mul(w, h)),
        _ => None,
    })
}

/// The compressions the `tiled` crate reads (with base64 encoding).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Compression {
    Zlib,
    Gzip,
}

impl Compression {
    /// The compression of a base64 `<data ...>` tag, if zlib or gzip.
    fn of(tag: &[u8]) -> Result<Option<Self>, String> {
        Ok(match attribute(tag, b"compression")?.as_deref() {
            Some(b"zlib") => Some(Self::Zlib),
            Some(b"gzip") => Some(Self::Gzip),
            _ => None,
        })
    }

    /// How many bytes `text` (base64) expands to, if at most `budget`.
    fn expand(self, text: &[u8], budget: u64) -> Result<u64, String> {
        use base64::Engine;
        let data = base64::engine::general_purpose::STANDARD
            .decode(text)
            .map_err(|e| format!("has tile data that is not base64: {e}"))?;
        let reader: Box<dyn Read> = match self {
            Self::Zlib => Box::new(flate2::bufread::ZlibDecoder::new(&data[..])),
            Self::Gzip => Box::new(flate2::bufread::GzDecoder::new(&data[..])),
        };
        let n = std::io::copy(&mut reader.take(budget + 1), &mut std::io::sink())
            .map_err(|e| format!("has compressed tile data that does not decompress: {e}"))?;
        if n > budget {
            return Err(format!(
                "has compressed tile data that expands to more than {} MiB",
                MAX_TILE_DATA_BYTES >> 20
            ));
        }
        Ok(n)
    }
}

/// Where `needle` starts in `hay`.
fn find(hay: &[u8], needle: &[u8]) -> Result<usize, String> {
    hay.windows(needle.len())
        .position(|w| w == needle)
        .ok_or_else(|| "ends inside a tag or comment".to_owned())
}

/// The index of the `>` that ends the tag `tag` starts, past quoted
/// attribute values.
fn tag_end(tag: &[u8]) -> Result<usize, String> {
    let mut quote = None;
    for (k, &b) in tag.iter().enumerate() {
        match (quote, b) {
            (None, b'"' | b'\'') => quote = Some(b),
            (Some(q), _) if b == q => quote = None,
            (None, b'>') => return Ok(k),
            _ => {}
        }
    }
    Err("ends inside a tag".to_owned())
}

/// A tag's name: up to the first space, `/` or end.
fn name(tag: &[u8]) -> &[u8] {
    let end = tag
        .iter()
        .position(|b| b.is_ascii_whitespace() || *b == b'/')
        .unwrap_or(tag.len());
    &tag[..end]
}

/// A name without its namespace prefix (`x:data` is `data`).
fn local(name: &[u8]) -> &[u8] {
    name.rsplit(|&b| b == b':').next().unwrap_or(name)
}

/// The value of attribute `key` in a tag, by its local name, unescaped
/// (without its quotes).
fn attribute(tag: &[u8], key: &[u8]) -> Result<Option<Vec<u8>>, String> {
    let mut rest = &tag[name(tag).len()..];
    loop {
        rest = rest.trim_ascii_start();
        let Some(eq) = rest.iter().position(|&b| b == b'=') else {
            return Ok(None);
        };
        let found = rest[..eq].trim_ascii_end();
        let value = rest[eq + 1..].trim_ascii_start();
        let Some(&quote) = value.first() else {
            return Ok(None);
        };
        let Some(close) = value[1..].iter().position(|&b| b == quote) else {
            return Ok(None);
        };
        if local(found) == key {
            return unescape(&value[1..1 + close]).map(Some);
        }
        rest = &value[close + 2..];
    }
}

/// XML text with its entity references (`&amp;`, `&#108;`, `&#x6C;`, ...)
/// replaced by what they stand for.
fn unescape(text: &[u8]) -> Result<Vec<u8>, String> {
    if !text.contains(&b'&') {
        return Ok(text.to_vec());
    }
    let mut out = Vec::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.iter().position(|&b| b == b'&') {
        out.extend_from_slice(&rest[..at]);
        let semi = rest[at..]
            .iter()
            .position(|&b| b == b';')
            .ok_or("has an entity reference with no `;`")?;
        let entity = &rest[at + 1..at + semi];
        let number = |digits: &[u8], radix: u32| {
            std::str::from_utf8(digits)
                .ok()
                .and_then(|d| u32::from_str_radix(d, radix).ok())
                .and_then(char::from_u32)
        };
        let c = match entity {
            b"amp" => Some('&'),
            b"lt" => Some('<'),
            b"gt" => Some('>'),
            b"quot" => Some('"'),
            b"apos" => Some('\''),
            [b'#', b'x' | b'X', hex @ ..] => number(hex, 16),
            [b'#', dec @ ..] => number(dec, 10),
            _ => None,
        };
        let c = c.ok_or_else(|| {
            format!(
                "has an entity reference it cannot read: &{};",
                String::from_utf8_lossy(entity)
            )
        })?;
        let mut buf = [0; 4];
        out.extend_from_slice(c.encode_utf8(&mut buf).as_bytes());
        rest = &rest[at + semi + 1..];
    }
    out.extend_from_slice(rest);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    fn zlib(bytes: &[u8]) -> String {
        use base64::Engine;
        let mut e = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::best());
        e.write_all(bytes).unwrap();
        base64::engine::general_purpose::STANDARD.encode(e.finish().unwrap())
    }

    fn map(data: &str) -> String {
        format!(
            r#"<?xml version="1.0"?><!-- a <comment> --><map a="x>y"><layer><data encoding="base64" compression="zlib">{data}</data></layer></map>"#
        )
    }

    #[test]
    fn json_values_are_counted_outside_strings() {
        assert_eq!(json_values(b"7", 10), Some(1));
        assert_eq!(json_values(b"[1, 2, 3]", 10), Some(4));
        assert_eq!(json_values(br#"{"a": [], "b": {}}"#, 10), Some(5));
        // Commas, brackets and escaped quotes inside strings do not count.
        assert_eq!(json_values(br#"["{,[", "\"{,", "\\", 1]"#, 10), Some(5));
        assert_eq!(json_values(b"[1, 2, 3]", 3), None);
        assert_eq!(json_values(&b"{},".repeat(1000), 10_000), Some(2001));
    }

    #[test]
    fn a_plain_map_passes_and_its_compressed_data_is_counted() {
        assert_eq!(check_xml(map(&zlib(&[0; 4096])).as_bytes()), Ok(()));
        assert_eq!(check_xml(b"<map><layer/><layer></layer></map>"), Ok(()));
    }

    #[test]
    fn deep_nesting_is_refused_at_the_limit() {
        let nest = |n: usize| "<group>".repeat(n) + &"</group>".repeat(n);
        assert_eq!(check_xml(nest(MAX_XML_DEPTH).as_bytes()), Ok(()));
        let err = check_xml(nest(MAX_XML_DEPTH + 1).as_bytes()).unwrap_err();
        assert!(err.contains("64 deep"), "{err}");
        // Self-closing tags and closed siblings do not add up.
        let flat = "<g/>".repeat(1000) + &"<g></g>".repeat(1000);
        assert_eq!(check_xml(flat.as_bytes()), Ok(()));
    }

    fn zeros(mib: usize) -> String {
        use base64::Engine;
        let mut e = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::fast());
        let chunk = vec![0u8; 1 << 20];
        for _ in 0..mib {
            e.write_all(&chunk).unwrap();
        }
        base64::engine::general_purpose::STANDARD.encode(e.finish().unwrap())
    }

    #[test]
    fn data_that_expands_past_the_budget_is_refused() {
        // 257 MiB of zeros compress to about a megabyte.
        let err = check_xml(map(&zeros(257)).as_bytes()).unwrap_err();
        assert!(err.contains("more than 256 MiB"), "{err}");
        assert_eq!(check_xml(map(&zeros(2)).as_bytes()), Ok(()));
    }

    #[test]
    fn the_budget_is_the_whole_files_in_text_and_cdata() {
        let mib = zeros(1);
        let budget = 2 << 20;
        let two = format!(
            r#"<map><layer><data encoding="base64" compression="zlib">{mib}</data></layer><layer><data compression="zlib" encoding="base64">{mib}</data></layer></map>"#
        );
        assert_eq!(scan(two.as_bytes(), budget), Ok(()));
        let cdata = format!(
            r#"<layer><data encoding="base64" compression="zlib"><![CDATA[{mib}]]></data></layer></map>"#
        );
        let three = two.replace("</map>", &cdata);
        assert!(scan(three.as_bytes(), budget).is_err());
        assert_eq!(scan(three.as_bytes(), 3 << 20), Ok(()));
        // Outside a compressed `<data>` the same text is not counted.
        let after = two.replace("</map>", &format!("<name>{mib}</name></map>"));
        assert_eq!(scan(after.as_bytes(), budget), Ok(()));
    }

    #[test]
    fn broken_tags_and_bad_data_are_errors() {
        assert!(check_xml(b"<map a=\"x").is_err());
        assert!(check_xml(b"<!-- never closed").is_err());
        assert!(check_xml(map("not base64!").as_bytes()).is_err());
        assert!(check_xml(map("AAAA").as_bytes()).is_err());
        // Uncompressed and CSV data are left to the parser.
        assert_eq!(
            check_xml(br#"<data encoding="csv">1,2</data><data encoding="base64">AAAA</data>"#),
            Ok(())
        );
    }

    #[test]
    fn attributes_are_read_in_any_order_and_quote() {
        let tag = br#"data  compression = 'gzip' encoding="base64""#;
        assert_eq!(attribute(tag, b"encoding"), Ok(Some(b"base64".to_vec())));
        assert_eq!(Compression::of(tag), Ok(Some(Compression::Gzip)));
        assert_eq!(Compression::of(br#"data encoding="base64""#), Ok(None));
        assert_eq!(attribute(br#"data x="1"#, b"x"), Ok(None));
    }

    #[test]
    fn a_layer_whose_first_section_of_text_is_short_is_refused() {
        // The `tiled` crate reads a `<data>`'s text up to the first
        // element, comment or CDATA section, and indexes the layer by its
        // size: a short first section panicked inside it (found by the
        // `tmx` fuzz target), though the sections together hold enough.
        let layer = |data: &str| {
            format!(
                r#"<map><layer width="2" height="2"><data encoding="csv">{data}</data></layer></map>"#
            )
        };
        for data in [
            "1,1<property/>,1,1",
            "1<!-- -->,1,1,1",
            "1,1<![CDATA[,1,1]]>",
            "\n<![CDATA[1,1,1,1]]>",
            // A `<layer>` inside the data does not change the size the
            // data must fill (found by the `tmx` fuzz target too).
            r#"1,1<layer width="1" height="1">,1,1"#,
            r#"1,1<layer width="x">,1,1"#,
        ] {
            let err = check_xml(layer(data).as_bytes()).unwrap_err();
            assert!(err.contains("4 cells"), "{data}: {err}");
        }
        for data in [
            "1,1,1,1",
            "<![CDATA[1,1,1,1]]>",
            "1,1,1,1<!-- -->",
            "<!-- -->1,1,1,1",
        ] {
            assert_eq!(check_xml(layer(data).as_bytes()), Ok(()), "{data}");
        }
    }

    #[test]
    fn prefixes_entities_and_nesting_do_not_hide_compressed_data() {
        // Each of these expands 3 MiB under a budget of 2: the `tiled`
        // crate reads names by their local part, unescapes attribute
        // values and text, and decodes the text of a `<data>` around an
        // element inside it.
        let mib3 = zeros(3);
        let budget = 2 << 20;
        for file in [
            format!(r#"<map><x:data encoding="base64" compression="zlib">{mib3}</x:data></map>"#),
            format!(r#"<map><data encoding="base64" y:compression="zlib">{mib3}</data></map>"#),
            format!(r#"<map><data encoding="base64" compression="z&#108;ib">{mib3}</data></map>"#),
            format!(r#"<map><data encoding="base&#x36;4" compression="zlib">{mib3}</data></map>"#),
            format!(
                r#"<map><data encoding="base64" compression="zlib"><data></data>{mib3}</data></map>"#
            ),
        ] {
            let err = scan(file.as_bytes(), budget).unwrap_err();
            assert!(err.contains("more than"), "{err}");
        }
        // The parser decodes the first section of text alone: a comment
        // ends it, so half a stream is all it reads, and so does the scan.
        let mib1 = zeros(1);
        let (head, tail) = mib1.split_at(mib1.len() / 2);
        let commented = format!(
            r#"<map><data encoding="base64" compression="zlib">{head}<!-- a note -->{tail}</data></map>"#
        );
        let err = scan(commented.as_bytes(), budget).unwrap_err();
        assert!(err.contains("does not decompress"), "{err}");
        // A character reference does not end a section.
        let escaped = format!(
            r#"<map><data encoding="base64" compression="zlib">&#10;{mib1}&#10;</data></map>"#
        );
        assert_eq!(scan(escaped.as_bytes(), budget), Ok(()));
        assert!(unescape(b"&bogus;").is_err() && unescape(b"a & b").is_err());
        assert_eq!(unescape(b"&lt;&amp;&#x41;&#66;"), Ok(b"<&AB".to_vec()));
    }

    #[test]
    fn infinite_maps_chunks_huge_tilesets_and_too_many_objects_are_refused() {
        assert!(check_xml(br#"<map infinite="1"></map>"#).is_err());
        assert_eq!(check_xml(br#"<map infinite="0"></map>"#), Ok(()));
        assert!(check_xml(br#"<data encoding="csv"><chunk x="0">1</chunk></data>"#).is_err());
        let set = |n: u64| format!(r#"<tileset tilecount="{n}"/>"#);
        assert_eq!(check_xml(set(MAX_TILESET_TILES).as_bytes()), Ok(()));
        assert!(check_xml(set(MAX_TILESET_TILES + 1).as_bytes()).is_err());
        let objects = |n: u64| format!("<g>{}</g>", "<object/>".repeat(n as usize));
        assert_eq!(check_xml(objects(MAX_OBJECTS).as_bytes()), Ok(()));
        assert!(check_xml(objects(MAX_OBJECTS + 1).as_bytes()).is_err());
        let braces = |n: u64| format!("[{}]", vec!["{}"; n as usize].join(","));
        assert!(json_values(braces(MAX_OBJECTS).as_bytes(), u64::MAX).is_some());
        assert!(json_values(braces(MAX_OBJECTS + 1).as_bytes(), u64::MAX).is_none());
    }
}
