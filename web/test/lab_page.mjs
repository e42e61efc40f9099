// The lab's page as the browser tests drive it: its status (gui.h, guiStatusJson), a step
// settled, the editor typed into, a file the page wrote read back.
export function labPage(page) {
  const status = async () => JSON.parse(await page.evaluate(
      `typeof pbrlabPage === 'object' && pbrlabPage.running ? pbrlabPage.status() : '{}'`));
  const settledOn = async (id) => {
    const s = await status();
    return s.step === id && s.settled ? s : null;
  };
  return {
    status,
    settledOn,
    // Replaces the editor's text, typed as a student would.
    typeFile: async (text) => {
      await page.evaluate(`pbrlabPage.focusEditor()`);
      await page.send('Input.dispatchKeyEvent', {type: 'keyDown', key: 'a', code: 'KeyA',
                                                 modifiers: 2, commands: ['selectAll']});
      await page.type(text);
    },
    // The step settled with a student's file: its row, then the solution's.
    studentRows: (id) => page.until(async () => {
      const s = await settledOn(id);
      return s && s.rows.length === 2 ? s : null;
    }, 120000, `${id} with a student file to settle`),
    // A file of the page's file system, as bytes.
    readFile: async (file) => Buffer.from(await page.evaluate(`(() => {
      const bytes = FS.readFile('${file}');
      let text = '';
      for (let i = 0; i < bytes.length; i += 8192)
        text += String.fromCharCode.apply(null, bytes.subarray(i, i + 8192));
      return btoa(text);
    })()`), 'base64'),
  };
}
