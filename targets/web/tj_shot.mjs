import {serve, launchChromium, openPage} from "./harness.mjs";
const {browser, close} = await launchChromium("/usr/bin/chromium");
const server = await serve({web: "/work/wt/threejs/web"});
const {page, problems} = await openPage(browser, `http://127.0.0.1:${server.address().port}/web/three/example/index.html?size=960x600`, "example", {width: 960, height: 600});
page.on("console", (m) => console.log("console:", m.type(), m.text()));
await page.evaluate(() => window.example.ready);
for (const [name, changes] of JSON.parse(process.argv[2])) {
  await page.evaluate((c) => window.example.set(c), changes);
  await page.screenshot({path: `/work/wt/notes/threejs/${name}.png`});
}
console.log(problems, await page.evaluate(() => window.example.info()));
await close(); server.close();
