// Debian's headless Chromium through puppeteer-core, drawing WebGL with
// SwiftShader (no GPU on the test machines), for the browser tests.
import puppeteer from 'puppeteer-core';

// Thrown when Chromium cannot start: the browser tests then skip (exit 77).
export class ChromiumCannotStart extends Error {}

export async function launchChromium(chromium = '/usr/bin/chromium') {
  try {
    return await puppeteer.launch({
      executablePath: chromium, headless: true,
      args: ['--no-sandbox', '--enable-unsafe-swiftshader', '--use-angle=swiftshader', '--ignore-gpu-blocklist'],
    });
  } catch (e) {
    throw new ChromiumCannotStart(`chromium (${chromium}) cannot start: ${e.message.split('\n')[0]}`);
  }
}
