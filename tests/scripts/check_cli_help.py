"""Every option of every command of the given programs has a line of --help (args.h OptionHelp).

usage: check_cli_help.py PROGRAM...   (e.g. build/bin/macrocon build/bin/macrocon-eval)
Commands come from each program's own list (PROGRAM --help); a command whose usage names
subcommands (macrocon library build | add | info) is checked per subcommand.
"""
import re
import subprocess
import sys

COLUMN = 30  # args.cpp's CLI11 column width


def undescribed(help_text):
    """Options in the 'Options:' list of help_text with no description."""
    lines = help_text.split("\n")
    if "Options:" not in lines:
        return ["(no 'Options:' list)"]
    lines = lines[lines.index("Options:") + 1:]
    out = []
    for i, line in enumerate(lines):
        if not line.startswith("  -"):
            continue
        same_line = line[COLUMN:].strip() if len(line) > COLUMN else ""
        # A name wider than the column puts its description on the next, indented line.
        nxt = lines[i + 1] if i + 1 < len(lines) else ""
        next_line = nxt.strip() if nxt.startswith(" " * COLUMN) and not nxt.lstrip().startswith("-") else ""
        if len(line.rstrip()) > COLUMN and not line[COLUMN - 1] == " ":
            same_line = ""  # the name itself runs past the column
        if not same_line and not next_line:
            out.append(line.split()[0])
    return out


def run(args):
    p = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        sys.exit("%s failed (%d): %s" % (" ".join(args), p.returncode, p.stderr))
    return p.stdout


def main():
    # The check must catch an option without a line (else it proves nothing).
    fixture = "Options:\n  -h,--help                   print this help and exit\n  --radius R                  \n"
    if undescribed(fixture) != ["--radius"]:
        sys.exit("self-check: an option without a description was not caught: %r" % undescribed(fixture))
    failures, checked = [], 0
    for program in sys.argv[1:]:
        name = program.rsplit("/", 1)[-1]
        commands = re.findall(r"^  (\S+)\s{2,}\S", run([program, "--help"]), re.M)
        for command in commands:
            if command == "help":
                continue
            text = run([program, "help", command])
            subs = sorted(set(re.findall(r"%s %s (\w+)" % (re.escape(name), re.escape(command)), text)))
            for sub in subs or [None]:
                words = [command] + ([sub] if sub else [])
                missing = undescribed(run([program, "help"] + words))
                checked += 1
                if missing:
                    failures.append("%s %s: %s" % (name, " ".join(words), ", ".join(missing)))
    print("checked the --help of %d commands" % checked)
    if checked == 0:
        sys.exit("no command found")
    if failures:
        sys.exit("options without a line of --help (add it to the command's OptionHelp):\n  " + "\n  ".join(failures))


if __name__ == "__main__":
    main()
