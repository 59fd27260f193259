// The editor (CodeMirror with the .l highlighting and the lint gutter), in a module of its
// own: main.js loads it while the first picture is on its way and builds it after that
// picture is drawn, so that opening the page does not wait for the editor's script.
import { EditorView, basicSetup } from 'codemirror';
import { setDiagnostics, lintGutter } from '@codemirror/lint';
import { lsystemLanguage } from './lsystem_language.js';

// An editor in `parent` holding `doc`; `changed(update)` hears every change of its text.
export function createEditor(parent, doc, changed) {
  return new EditorView({
    doc,
    extensions: [
      basicSetup, lsystemLanguage, lintGutter(),
      EditorView.updateListener.of((u) => { if (u.docChanged) changed(u); }),
    ],
    parent,
  });
}

// The editor's underlines: [{from, to, severity, message}].
export function underline(editor, diagnostics) {
  editor.dispatch(setDiagnostics(editor.state, diagnostics));
}
