// emitted_files.js — the page's files section: the emitted files of either side, the text of the
// chosen one, and links that download it or all of them.

const $ = (id) => document.getElementById(id);

export function showFiles(app) {
    const select = $("file"), side = app.sides[Number($("file-side").value)] || app.sides[0];
    const files = side.emission && side.emission.ok ? side.emission.files : {};
    const current = select.value;
    select.replaceChildren(...Object.keys(files).map((name) => Object.assign(document.createElement("option"), {value: name, textContent: name})));
    if (files[current] !== undefined) select.value = current;
    else if (files["layout.json"] !== undefined) select.value = "layout.json";
    const text = files[select.value] ?? (side.emission ? side.emission.error : "");
    $("file-text").textContent = text;
    const link = $("download");
    if (link.href) URL.revokeObjectURL(link.href);
    link.href = URL.createObjectURL(new Blob([text], {type: "text/plain"}));
    link.download = select.value || "error.txt";
    $("download-all").onclick = (event) => {
        event.preventDefault();
        for (const [name, body] of Object.entries(files)) {
            const a = Object.assign(document.createElement("a"), {href: URL.createObjectURL(new Blob([body])), download: name});
            a.click();
            URL.revokeObjectURL(a.href);
        }
    };
}
